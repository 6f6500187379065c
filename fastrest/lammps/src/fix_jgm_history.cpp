#include "fix_jgm_history.h"

#include "atom.h"
#include "error.h"
#include "neigh_list.h"

#include <cmath>

using namespace LAMMPS_NS;
using namespace FixConst;

FixJGMHistory::FixJGMHistory(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), nvalues(0), flip_lo(0), flip_hi(0), list(nullptr), current(false)
{
  // fix ID group jgm/history NVALUES FLIP_LO FLIP_HI
  if (narg != 6)
    error->all(FLERR, "fix jgm/history: expected 3 arguments (values per contact, first and end of the "
                      "values negated for the partner), got {}", narg - 3);
  nvalues = utils::inumeric(FLERR, arg[3], false, lmp);
  flip_lo = utils::inumeric(FLERR, arg[4], false, lmp);
  flip_hi = utils::inumeric(FLERR, arg[5], false, lmp);
  if (nvalues < 1 || nvalues > 64) error->all(FLERR, "fix jgm/history: values per contact {} not in 1..64", nvalues);
  if (flip_lo < 0 || flip_hi < flip_lo || flip_hi > nvalues)
    error->all(FLERR, "fix jgm/history: negated values {}..{} not within 0..{}", flip_lo, flip_hi, nvalues);
  restart_peratom = 1;
  create_attribute = 1;
  maxexchange = 1 + MAXPARTNER * (1 + nvalues);
  grow_arrays(atom->nmax);
  atom->add_callback(Atom::GROW);
  atom->add_callback(Atom::RESTART);
}

FixJGMHistory::~FixJGMHistory()
{
  atom->delete_callback(id, Atom::GROW);
  atom->delete_callback(id, Atom::RESTART);
}

int FixJGMHistory::setmask()
{
  return PRE_EXCHANGE | POST_NEIGHBOR | POST_RUN | MIN_PRE_EXCHANGE | MIN_POST_NEIGHBOR;
}

void FixJGMHistory::add_partner(int i, double tag, const double *v, bool flip)
{
  std::vector<double> &p = partners[i];
  if (p.size() >= static_cast<size_t>(MAXPARTNER * (1 + nvalues)))
    error->one(FLERR, "pair jgm: atom {} has more than {} contacts", atom->tag[i], MAXPARTNER);
  p.push_back(tag);
  p.insert(p.end(), v, v + nvalues);
  if (flip)
    for (int k = flip_lo; k < flip_hi; ++k) p[p.size() - nvalues + k] = -p[p.size() - nvalues + k];
}

void FixJGMHistory::to_atoms()
{
  int nlocal = atom->nlocal;
  for (int i = 0; i < nlocal; ++i) partners[i].clear();
  if (!list || !current) return;
  tagint *tag = atom->tag;
  for (int ii = 0; ii < list->inum; ++ii) {
    int i = list->ilist[ii];
    int *jlist = list->firstneigh[i];
    const double *v = values(i);
    for (int jj = 0; jj < list->numneigh[i]; ++jj, v += nvalues) {
      bool active = false;
      for (int k = 0; k < nvalues; ++k) active = active || v[k] != 0.0;
      if (!active) continue;
      int j = jlist[jj] & NEIGHMASK;
      add_partner(i, static_cast<double>(tag[j]), v, false);
      if (j < nlocal) add_partner(j, static_cast<double>(tag[i]), v, true);
    }
  }
}

void FixJGMHistory::pre_exchange() { to_atoms(); }
void FixJGMHistory::min_pre_exchange() { to_atoms(); }
void FixJGMHistory::post_run() { to_atoms(); }
void FixJGMHistory::setup_post_neighbor() { post_neighbor(); }
void FixJGMHistory::min_post_neighbor() { post_neighbor(); }

void FixJGMHistory::post_neighbor()
{
  if (!list) error->all(FLERR, "fix jgm/history is used by pair_style jgm only");
  int nlocal = atom->nlocal;
  tagint *tag = atom->tag;
  offset.assign(nlocal + 1, 0);
  size_t total = 0;
  for (int ii = 0; ii < list->inum; ++ii) {
    int i = list->ilist[ii];
    offset[i] = total;
    total += static_cast<size_t>(list->numneigh[i]) * nvalues;
  }
  vals.assign(total, 0.0);
  const size_t stride = 1 + nvalues;
  for (int ii = 0; ii < list->inum; ++ii) {
    int i = list->ilist[ii];
    const std::vector<double> &p = partners[i];
    if (p.empty()) continue;
    int *jlist = list->firstneigh[i];
    double *v = values(i);
    for (int jj = 0; jj < list->numneigh[i]; ++jj, v += nvalues) {
      double t = static_cast<double>(tag[jlist[jj] & NEIGHMASK]);
      for (size_t m = 0; m < p.size(); m += stride)
        if (p[m] == t) {
          for (int k = 0; k < nvalues; ++k) v[k] = p[m + 1 + k];
          break;
        }
    }
  }
  current = true;
}

void FixJGMHistory::grow_arrays(int nmax) { partners.resize(nmax); }

void FixJGMHistory::copy_arrays(int i, int j, int) { partners[j] = partners[i]; }

void FixJGMHistory::set_arrays(int i) { partners[i].clear(); }

int FixJGMHistory::pack_exchange(int i, double *buf)
{
  const std::vector<double> &p = partners[i];
  buf[0] = static_cast<double>(p.size());
  for (size_t m = 0; m < p.size(); ++m) buf[1 + m] = p[m];
  return 1 + static_cast<int>(p.size());
}

int FixJGMHistory::unpack_exchange(int nlocal, double *buf)
{
  int n = static_cast<int>(buf[0]);
  partners[nlocal].assign(buf + 1, buf + 1 + n);
  return 1 + n;
}

int FixJGMHistory::pack_restart(int i, double *buf)
{
  const std::vector<double> &p = partners[i];
  buf[0] = static_cast<double>(p.size() + 1);
  for (size_t m = 0; m < p.size(); ++m) buf[1 + m] = p[m];
  return 1 + static_cast<int>(p.size());
}

void FixJGMHistory::unpack_restart(int nlocal, int nth)
{
  double **extra = atom->extra;
  int m = 0;
  for (int k = 0; k < nth; ++k) m += static_cast<int>(extra[nlocal][m]);
  double n = extra[nlocal][m] - 1.0;
  if (!(n >= 0.0) || n > MAXPARTNER * (1 + nvalues) || std::fmod(n, 1.0 + nvalues) != 0.0)
    error->one(FLERR, "fix jgm/history: restart file holds a bad contact list for atom {}", atom->tag[nlocal]);
  partners[nlocal].assign(&extra[nlocal][m + 1], &extra[nlocal][m + 1] + static_cast<int>(n));
}

int FixJGMHistory::size_restart(int i) { return 1 + static_cast<int>(partners[i].size()); }

int FixJGMHistory::maxsize_restart() { return 1 + MAXPARTNER * (1 + nvalues); }

double FixJGMHistory::memory_usage()
{
  double bytes = static_cast<double>(vals.capacity()) * sizeof(double);
  for (const auto &p : partners) bytes += static_cast<double>(p.capacity()) * sizeof(double);
  return bytes;
}
