#include "fix_jgm_history.h"

#include "jgm_laws.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "pair.h"
#include "neigh_list.h"

#include <cmath>
#include <cstring>
#include <mpi.h>

using namespace LAMMPS_NS;
using namespace FixConst;

// first value of the global restart record: which layout follows ([magic, values per contact,
// length of the model, the model])
static constexpr double MODEL_MAGIC = 20261202.0;

FixJGMHistory::FixJGMHistory(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), restored_rows(false), nvalues(0), flip_lo(0), flip_hi(0), restored_nvalues(0), list(nullptr), current(false)
{
  // fix ID group jgm/history NVALUES FLIP_LO FLIP_HI
  if (narg != 6)
    error->all(FLERR, "fix jgm/history: expected 3 arguments (values per contact, first and end of the "
                      "values negated for the partner), got {}", narg - 3);
  nvalues = utils::inumeric(FLERR, arg[3], false, lmp);
  flip_lo = utils::inumeric(FLERR, arg[4], false, lmp);
  flip_hi = utils::inumeric(FLERR, arg[5], false, lmp);
  check_layout(error, nvalues, flip_lo, flip_hi);
  restored_nvalues = nvalues;
  restart_global = 1;
  restart_peratom = 1;
  create_attribute = 1;
  maxexchange_dynamic = 1;    // partner lists grow as needed: pre_exchange sizes the messages
  maxexchange = 2;
  grow_arrays(atom->nmax);
  atom->add_callback(Atom::GROW);
  atom->add_callback(Atom::RESTART);
}

FixJGMHistory::~FixJGMHistory()
{
  atom->delete_callback(id, Atom::GROW);
  atom->delete_callback(id, Atom::RESTART);
}

void FixJGMHistory::check_layout(Error *error, int nvalues, int flip_lo, int flip_hi)
{
  if (nvalues < 1 || nvalues > 64) error->all(FLERR, "fix jgm/history: values per contact {} not in 1..64", nvalues);
  if (flip_lo < 0 || flip_hi < flip_lo || flip_hi > nvalues)
    error->all(FLERR, "fix jgm/history: negated values {}..{} not within 0..{}", flip_lo, flip_hi, nvalues);
}

// keep each contact's first values, as many as both layouts have; the rest start at 0
static void resize_rows(std::vector<double> &p, int from, int to)
{
  if (from == to || p.empty()) return;
  std::vector<double> out;
  out.reserve(p.size() / (1 + from) * (1 + to));
  for (size_t c = 0; c + from < p.size(); c += 1 + from) {
    out.push_back(p[c]);
    for (int k = 0; k < to; ++k) out.push_back(k < from ? p[c + 1 + k] : 0.0);
  }
  p.swap(out);
}

void FixJGMHistory::relayout(int n, int lo, int hi)
{
  if (n == nvalues && lo == flip_lo && hi == flip_hi) return;
  check_layout(error, n, lo, hi);
  // between runs the open contacts are in the partner lists (post_run); the next set-up's
  // neighbour build spreads them over the list again
  for (int i = 0; i < atom->nlocal; ++i) resize_rows(partners[i], nvalues, n);
  nvalues = n;
  flip_lo = lo;
  flip_hi = hi;
  vals.clear();
  used.clear();
  current = false;
}

int FixJGMHistory::setmask()
{
  return PRE_EXCHANGE | POST_NEIGHBOR | POST_RUN | MIN_PRE_EXCHANGE | MIN_POST_NEIGHBOR;
}

void FixJGMHistory::add_partner(int i, double tag, const double *v, bool flip)
{
  std::vector<double> &p = partners[i];
  p.push_back(tag);
  p.insert(p.end(), v, v + nvalues);
  if (flip)
    for (int k = flip_lo; k < flip_hi; ++k) p[p.size() - nvalues + k] = -p[p.size() - nvalues + k];
}

void FixJGMHistory::to_atoms()
{
  int nlocal = atom->nlocal;
  for (int i = 0; i < nlocal; ++i) partners[i].clear();
  if (list && current) {
    tagint *tag = atom->tag;
    for (int ii = 0; ii < list->inum; ++ii) {
      int i = list->ilist[ii];
      int *jlist = list->firstneigh[i];
      const double *v = values(i);
      const unsigned char *u = in_use(i);
      for (int jj = 0; jj < list->numneigh[i]; ++jj, v += nvalues) {
        if (!u[jj]) continue;
        int j = jlist[jj] & NEIGHMASK;
        add_partner(i, static_cast<double>(tag[j]), v, false);
        if (j < nlocal) add_partner(j, static_cast<double>(tag[i]), v, true);
      }
    }
  }
  size_t most = 0;
  for (int i = 0; i < nlocal; ++i) most = std::max(most, partners[i].size());
  maxexchange = 2 + static_cast<int>(most);
}

void FixJGMHistory::pre_exchange() { to_atoms(); }
void FixJGMHistory::min_pre_exchange() { to_atoms(); }
void FixJGMHistory::post_run() { to_atoms(); }
void FixJGMHistory::setup_post_neighbor() { post_neighbor(); }
void FixJGMHistory::min_post_neighbor() { post_neighbor(); }

// Histories are found again by the partner's ID: an atom must never touch two images of one
// partner (a non-touching image in the list is told apart by distance, in post_neighbor)
void FixJGMHistory::check_box()
{
  static const char *axis = "xyz";
  double reach = force->pair ? force->pair->cutforce : 0.0;
  for (int d = 0; d < domain->dimension; ++d)
    if (domain->periodicity[d] && domain->prd[d] < 2.0 * reach)
      error->all(FLERR, "pair jgm: the periodic box is {:.6g} long in {} but two atoms touch up to {:.6g} apart "
                        "(the largest sum of radii): an atom could touch two images of one partner, whose "
                        "histories are matched by atom ID; make the box at least {:.6g} long in {}",
                 domain->prd[d], axis[d], reach, 2.0 * reach, axis[d]);
}

void FixJGMHistory::post_neighbor()
{
  if (!list) error->all(FLERR, "fix jgm/history is used by pair_style jgm only");
  check_box();
  int nlocal = atom->nlocal;
  tagint *tag = atom->tag;
  double **x = atom->x;
  offset.assign(nlocal + 1, 0);
  size_t total = 0;
  for (int ii = 0; ii < list->inum; ++ii) {
    int i = list->ilist[ii];
    offset[i] = total;
    total += static_cast<size_t>(list->numneigh[i]);
  }
  vals.assign(total * nvalues, 0.0);
  used.assign(total, 0);
  const size_t stride = 1 + nvalues;
  std::vector<int> taken;
  for (int ii = 0; ii < list->inum; ++ii) {
    int i = list->ilist[ii];
    const std::vector<double> &p = partners[i];
    if (p.empty()) continue;
    int *jlist = list->firstneigh[i];
    double *v = values(i);
    unsigned char *u = in_use(i);
    taken.assign(p.size() / stride, -1);
    for (int jj = 0; jj < list->numneigh[i]; ++jj) {
      int j = jlist[jj] & NEIGHMASK;
      double t = static_cast<double>(tag[j]);
      for (size_t m = 0; m < p.size(); m += stride) {
        if (p[m] != t) continue;
        int &at = taken[m / stride];
        if (at >= 0) {    // two images of the partner in the list: the nearer one is the contact
          int o = jlist[at] & NEIGHMASK;
          double dn = 0.0, dold = 0.0;
          for (int k = 0; k < 3; ++k) {
            dn += (x[i][k] - x[j][k]) * (x[i][k] - x[j][k]);
            dold += (x[i][k] - x[o][k]) * (x[i][k] - x[o][k]);
          }
          if (!(dn < dold)) break;
          for (int k = 0; k < nvalues; ++k) v[static_cast<size_t>(at) * nvalues + k] = 0.0;
          u[at] = 0;
        }
        at = jj;
        for (int k = 0; k < nvalues; ++k) v[static_cast<size_t>(jj) * nvalues + k] = p[m + 1 + k];
        u[jj] = FastrestJGM::row_open(p.data() + m + 1, nvalues);
        break;
      }
    }
  }
  current = true;
}

void FixJGMHistory::write_restart(FILE *fp)
{
  if (comm->me != 0) return;
  std::vector<double> rec;
  rec.push_back(MODEL_MAGIC);
  rec.push_back(static_cast<double>(nvalues));
  rec.push_back(static_cast<double>(model.size()));
  rec.insert(rec.end(), model.begin(), model.end());
  int size = static_cast<int>(rec.size() * sizeof(double));
  fwrite(&size, sizeof(int), 1, fp);
  fwrite(rec.data(), sizeof(double), rec.size(), fp);
}

void FixJGMHistory::restart(char *buf)
{
  // LAMMPS passes the record without its length: read only as far as the record itself says,
  // and no further than any model the pair style can write (PairJGM::model_record)
  double head[3];
  std::memcpy(head, buf, sizeof(head));
  double most = 8.0 + 4.0 * atom->ntypes;
  if (head[0] != MODEL_MAGIC || !(head[1] >= 1.0 && head[1] <= 64.0) || head[1] != std::floor(head[1]) ||
      !(head[2] >= 0.0 && head[2] <= most) || head[2] != std::floor(head[2]))
    error->all(FLERR, "fix jgm/history: the restart file's record of pair_style jgm's model is damaged or from "
                      "another version of the plugin (write the state with write_data there to continue here; "
                      "contacts then start anew)");
  restored_nvalues = static_cast<int>(head[1]);
  restored_model.resize(static_cast<size_t>(head[2]));
  std::memcpy(restored_model.data(), buf + sizeof(head), restored_model.size() * sizeof(double));
  for (double v : restored_model)
    if (!std::isfinite(v))
      error->all(FLERR, "fix jgm/history: the restart file's record of pair_style jgm's model holds a value "
                        "that is not finite");
}

void FixJGMHistory::grow_arrays(int nmax)
{
  partners.resize(nmax);
  ended_energy.resize(nmax, 0.0);
}

void FixJGMHistory::copy_arrays(int i, int j, int)
{
  partners[j] = partners[i];
  ended_energy[j] = ended_energy[i];
}

void FixJGMHistory::set_arrays(int i)
{
  partners[i].clear();
  ended_energy[i] = 0.0;
}

int FixJGMHistory::pack_exchange(int i, double *buf)
{
  const std::vector<double> &p = partners[i];
  buf[0] = static_cast<double>(p.size());
  buf[1] = ended_energy[i];
  for (size_t m = 0; m < p.size(); ++m) buf[2 + m] = p[m];
  return 2 + static_cast<int>(p.size());
}

int FixJGMHistory::unpack_exchange(int nlocal, double *buf)
{
  int n = static_cast<int>(buf[0]);
  ended_energy[nlocal] = buf[1];
  partners[nlocal].assign(buf + 2, buf + 2 + n);
  return 2 + n;
}

// restart record per atom: [2 + n, ended energy, n values of the partner list]
int FixJGMHistory::pack_restart(int i, double *buf)
{
  const std::vector<double> &p = partners[i];
  buf[0] = static_cast<double>(p.size() + 2);
  buf[1] = ended_energy[i];
  for (size_t m = 0; m < p.size(); ++m) buf[2 + m] = p[m];
  return 2 + static_cast<int>(p.size());
}

void FixJGMHistory::unpack_restart(int nlocal, int nth)
{
  // the restart file is read as hostile: every count within the atom's record, every value finite,
  // every partner an atom ID other than the atom's own (the rows' values are checked against the
  // law by the pair style at the first set-up)
  double *extra = atom->extra[nlocal];
  const double width = atom->nextra_store;
  tagint self = atom->tag[nlocal];
  int at = FastrestJGM::restart_record(extra, atom->nextra_store, nth);
  if (at < 0) error->one(FLERR, "fix jgm/history: restart file holds a damaged record for atom {}", self);
  double m = at, size = extra[at];
  double n = size - 2.0;
  const int stored = restored_nvalues;    // values per contact in the file
  if (!(n >= 0.0 && m + size <= width) || n != std::floor(n) || std::fmod(n, 1.0 + stored) != 0.0)
    error->one(FLERR, "fix jgm/history: restart file holds a bad contact list for atom {} (its length is "
                      "not a whole number of contacts within the record)", self);
  if (!std::isfinite(extra[at + 1]) || extra[at + 1] < 0.0)
    error->one(FLERR, "fix jgm/history: restart file holds a dissipated energy for atom {} that is not finite "
                      "and >= 0", self);
  ended_energy[nlocal] = extra[at + 1];
  partners[nlocal].assign(extra + at + 2, extra + at + 2 + static_cast<int>(n));
  std::vector<double> &p = partners[nlocal];
  for (size_t c = 0; c < p.size(); c += 1 + stored) {
    double t = p[c];
    if (!(t >= 1.0 && t <= static_cast<double>(MAXTAGINT)) || t != std::floor(t) || t == static_cast<double>(self))
      error->one(FLERR, "fix jgm/history: restart file holds a contact of atom {} with a partner ID {} that is "
                        "no other atom's", self, t);
    for (int k = 1; k <= stored; ++k)
      if (!std::isfinite(p[c + k]))
        error->one(FLERR, "fix jgm/history: restart file holds a contact of atom {} (partner {}) with a value "
                          "that is not finite", self, static_cast<tagint>(t));
  }
  // a file of the model with rolling or twisting read by one without (or the reverse)
  resize_rows(p, stored, nvalues);
  if (!p.empty()) restored_rows = true;
}

int FixJGMHistory::size_restart(int i) { return 2 + static_cast<int>(partners[i].size()); }

int FixJGMHistory::maxsize_restart()
{
  int most = 0;
  for (int i = 0; i < atom->nlocal; ++i) most = std::max(most, static_cast<int>(partners[i].size()));
  int all = 0;
  MPI_Allreduce(&most, &all, 1, MPI_INT, MPI_MAX, world);
  return 2 + all;
}

double FixJGMHistory::memory_usage()
{
  double bytes = static_cast<double>(vals.capacity() + ended_energy.capacity()) * sizeof(double) + used.capacity();
  for (const auto &p : partners) bytes += static_cast<double>(p.capacity()) * sizeof(double);
  return bytes;
}
