#include "pair_jgm.h"

#include "fix_jgm_history.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "force.h"
#include "memory.h"
#include "modify.h"
#include "neigh_list.h"
#include "neighbor.h"
#include "update.h"

#include "fastrest_law.h"
#include "jgm_tangential.h"

#include <cmath>
#include <cstring>
#include <mpi.h>
#include <sstream>

using namespace LAMMPS_NS;
using FastrestJGM::Body;

static const char *HISTORY_ID = "FASTREST_JGM_HISTORY";

PairJGM::PairJGM(LAMMPS *lmp) :
    Pair(lmp), unloading_model("jcg"), neighprev(0), history(nullptr)
{
  nextra = 2;    // compute pair jgm: [1] energy dissipated in contacts, [2] elastic energy they hold
  pvector = new double[2];
  pvector[0] = pvector[1] = 0.0;
  single_enable = 1;    // compute pair/local: per-contact values (svector, see single())
  single_extra = NSINGLE;
  svector = new double[NSINGLE];
  restartinfo = 0;    // pair_style and pair_coeff are given again after read_restart
  finitecutflag = 1;
  no_virial_fdotr_compute = 1;    // forces on ghosts stay 0 (newton-off list): sum pair by pair
}

PairJGM::~PairJGM()
{
  delete[] pvector;
  delete[] svector;
  if (allocated) {
    memory->destroy(setflag);
    memory->destroy(cutsq);
  }
  if (modify->get_fix_by_id(HISTORY_ID)) modify->delete_fix(HISTORY_ID);
}

void PairJGM::allocate()
{
  allocated = 1;
  int n = atom->ntypes + 1;
  memory->create(setflag, n, n, "pair:setflag");
  memory->create(cutsq, n, n, "pair:cutsq");
  // setflag[i][i] = 1 for every type: LAMMPS's generic "All pair coeffs are not set" would come
  // first otherwise; init_style names the type that has no material
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) setflag[i][j] = (i == j);
  mat.assign(n, Body{0.0, 0.0, 0.0, 0.0});
  mat_set.assign(n, 0);
}

void PairJGM::settings(int narg, char **arg)
{
  unloading_model = "jcg";
  model = FastrestJGM::ContactModel();
  double &mu = model.mu;
  FastrestJGM::Resistance &res = model.res;
  int k = 0;
  while (k < narg) {
    std::string key = arg[k];
    if (key == "unloading") {
      if (k + 1 >= narg) error->all(FLERR, "pair_style jgm: 'unloading' needs a model: jcg, etsion or brake");
      std::string m = arg[k + 1];
      if (m != "jcg" && m != "etsion" && m != "brake")
        error->all(FLERR, "pair_style jgm: unloading model '{}' is not one of jcg, etsion, brake", m);
      unloading_model = m;
      k += 2;
    } else if (key == "tangential") {
      if (k + 1 >= narg) error->all(FLERR, "pair_style jgm: 'tangential' needs a model: none or mindlin MU");
      std::string m = arg[k + 1];
      if (m == "none") {
        mu = -1.0;
        k += 2;
      } else if (m == "mindlin") {
        if (k + 2 >= narg) error->all(FLERR, "pair_style jgm: 'tangential mindlin' needs the friction coefficient MU");
        mu = FastrestJGM::finite_number(lmp, "pair_style jgm", "MU", arg[k + 2]);
        if (!(mu >= 0.0))
          error->all(FLERR, "pair_style jgm: friction coefficient MU = {} must be finite and >= 0", arg[k + 2]);
        k += 3;
      } else {
        error->all(FLERR, "pair_style jgm: tangential model '{}' is not none or mindlin", m);
      }
    } else if (key == "rolling" || key == "twisting") {
      k = FastrestJGM::read_resistance(lmp, "pair_style jgm", narg, arg, k, res);
    } else {
      error->all(FLERR, "pair_style jgm: unknown keyword '{}' (expected unloading, tangential, rolling or twisting)",
                 key);
    }
  }
  if (res.twist == FastrestJGM::Resistance::MARSHALL && mu < 0.0)
    error->all(FLERR, "pair_style jgm: 'twisting marshall' takes its stiffness and limit from the tangential model: "
                      "give 'tangential mindlin MU' too");
}

void PairJGM::coeff(int narg, char **arg)
{
  if (narg != 5 && narg != 7)
    error->all(FLERR, "pair_coeff jgm: expected 'I J E nu Sy [Et value]' (5 or 7 arguments), got {}", narg);
  if (!allocated) allocate();
  int ilo, ihi, jlo, jhi;
  utils::bounds(FLERR, arg[0], 1, atom->ntypes, ilo, ihi, error);
  utils::bounds(FLERR, arg[1], 1, atom->ntypes, jlo, jhi, error);
  if (narg == 7 && std::strcmp(arg[5], "Et") != 0)
    error->all(FLERR, "pair_coeff jgm: expected keyword 'Et' after Sy, got '{}'", arg[5]);
  Body b = FastrestJGM::read_body(lmp, "pair_coeff jgm", arg[2], arg[3], arg[4], narg == 7 ? arg[6] : nullptr);
  int count = 0;
  for (int i = ilo; i <= ihi; ++i)
    for (int j = std::max(jlo, i); j <= jhi; ++j) {
      if (i != j) continue;
      mat[i] = b;
      mat_set[i] = 1;
      ++count;
    }
  if (count == 0)
    error->all(FLERR, "pair_coeff jgm: give each type's material as 'pair_coeff I I ...'; pairs of "
                      "different types take JGM's two-body rules from their materials");
}

const Body *PairJGM::material(int t) const
{
  if (!allocated || t < 1 || t > atom->ntypes || !mat_set[t]) return nullptr;
  return &mat[t];
}

void PairJGM::init_style()
{
  if (!atom->radius_flag || !atom->omega_flag || !atom->torque_flag)
    error->all(FLERR, "pair_style jgm needs per-atom radius, omega and torque (atom_style sphere)");
  if (FastrestJGM::pascal_per_unit(update->unit_style) <= 0.0)
    error->all(FLERR, "pair_style jgm: units {} have no meaning for a continuum contact law of macroscopic "
                      "spheres; use units si, cgs, micro or nano", update->unit_style);
  neighbor->add_request(this, NeighConst::REQ_SIZE | NeighConst::REQ_NEWTON_OFF);

  Fix *f = modify->get_fix_by_id(HISTORY_ID);
  // ghost atoms carry velocities (comm_modify vel yes): a contact's first step of work needs them;
  // set before comm->init() sizes the messages
  comm->ghost_velocity = 1;
  // the vectors from j to i are negated for j: H_F up to the row's end without rolling, to H_R with
  const int nh = nhist(), flip_hi = model.res.any() ? H_R : NHIST_SLIDE;
  if (!f) f = modify->add_fix(fmt::format("{} all jgm/history {} {} {}", HISTORY_ID, nh, H_F, flip_hi));
  history = dynamic_cast<FixJGMHistory *>(f);
  if (!history) error->all(FLERR, "fix ID {} is reserved for pair_style jgm", HISTORY_ID);
  // rolling or twisting switched on or off since the last run: the open contacts keep their normal
  // and sliding history; rolling and twisting springs start at rest (or are dropped)
  history->relayout(nh, H_F, flip_hi);

  // the largest radius of each type, as pair granular finds it: the atoms there now and any fix
  // that will insert atoms of the type (fix pour, fix deposit: extract("radius", type)); the
  // neighbour cutoff of two types is the sum of theirs
  int n = atom->ntypes;
  std::vector<double> local(n + 1, 0.0);
  for (Fix *fix : modify->get_fix_list())
    for (int t = 1; t <= n; ++t) {
      int dim = t;
      auto *r = static_cast<double *>(fix->extract("radius", dim));
      if (r && dim == 0 && std::isfinite(*r)) local[t] = std::max(local[t], *r);
    }
  for (int i = 0; i < atom->nlocal; ++i) {
    int t = atom->type[i];
    // LAMMPS takes a restart file's types as they are: a damaged one must not index the laws
    if (t < 1 || t > n) error->one(FLERR, "pair jgm: atom {} has type {}, not in 1..{}", atom->tag[i], t, n);
    double r = atom->radius[i];
    if (!(r > 0.0 && std::isfinite(r)))
      error->one(FLERR, "pair jgm: atom {} has radius {}, which must be finite and > 0", atom->tag[i], r);
    local[t] = std::max(local[t], r);
  }
  onerad.assign(n + 1, 0.0);
  MPI_Allreduce(local.data(), onerad.data(), n + 1, MPI_DOUBLE, MPI_MAX, world);
  build_laws();
  history->model = model_record();
  check_restored_model();
}

std::vector<double> PairJGM::model_record() const
{
  int n = atom->ntypes;
  std::vector<double> rec = {static_cast<double>(n), static_cast<double>(FastrestJGM::unloading_index(unloading_model)),
                             model.mu};
  for (int t = 1; t <= n; ++t) rec.insert(rec.end(), {mat[t].E, mat[t].nu, mat[t].Sy, mat[t].Et});
  return rec;
}

// A run read back from a restart file: its open contacts are histories of the model the file
// records; another material for a type with open contacts (or another unloading model) would
// reinterpret them silently
void PairJGM::check_restored_model()
{
  if (history->restored_model.empty()) return;
  const std::vector<double> old = history->restored_model;
  history->restored_model.clear();    // checked once, at the first run after read_restart
  int n = atom->ntypes;
  std::vector<int> open(n + 1, 0), all(n + 1, 0);
  for (int i = 0; i < atom->nlocal; ++i)
    if (history->partner_count(i) > 0) open[atom->type[i]] = 1;
  MPI_Allreduce(open.data(), all.data(), n + 1, MPI_INT, MPI_MAX, world);
  int any = 0;
  for (int t = 1; t <= n; ++t) any = any || all[t];
  if (!any) return;
  if (old.size() != static_cast<size_t>(3 + 4 * n) || old[0] != n)
    error->all(FLERR, "pair_style jgm: the restart file's model is not one of {} atom types (damaged)", n);
  const char *names[] = {"jcg", "etsion", "brake"};
  int was = static_cast<int>(old[1]);
  if (was != FastrestJGM::unloading_index(unloading_model))
    error->all(FLERR, "pair_style jgm: the restart file's open contacts follow unloading {}, this run gives "
                      "unloading {}: give 'pair_style jgm unloading {}' (or start them anew from a data file)",
               was >= 0 && was < 3 ? names[was] : "(damaged)", unloading_model, was >= 0 && was < 3 ? names[was] : "?");
  for (int t = 1; t <= n; ++t) {
    if (!all[t]) continue;
    const double *o = &old[3 + 4 * (t - 1)];
    if (o[0] != mat[t].E || o[1] != mat[t].nu || o[2] != mat[t].Sy || o[3] != mat[t].Et)
      error->all(FLERR, "pair_coeff jgm: atom type {} has open contacts in the restart file with material E {:.17g} "
                        "nu {:.17g} Sy {:.17g} Et {:.17g}; this run gives E {:.17g} nu {:.17g} Sy {:.17g} Et {:.17g}. "
                        "Give the restart's material, or continue from a data file (write_data), where contacts "
                        "start anew", t, o[0], o[1], o[2], o[3], mat[t].E, mat[t].nu, mat[t].Sy, mat[t].Et);
  }
}

// Every history row read from a restart file is one the law can have written: w_max* within the
// law's domain, P*(w_max), w_res* and delta those of the law at that w_max
void PairJGM::check_restored_rows()
{
  history->restored_rows = false;
  const int nh = nhist();
  int *type = atom->type;
  tagint *tag = atom->tag;
  int stride = atom->ntypes + 1;
  for (int ii = 0; ii < list->inum; ++ii) {
    int i = list->ilist[ii];
    int *jlist = list->firstneigh[i];
    const double *h = history->values(i);
    for (int jj = 0; jj < list->numneigh[i]; ++jj, h += nh) {
      if (!FastrestJGM::row_open(h, nh)) continue;
      int j = jlist[jj] & NEIGHMASK;
      std::string why = FastrestJGM::row_problem(laws, law_of[type[i] * stride + type[j]], h);
      if (why.empty() && !(h[H_Q] > 0.0 && h[H_Q] < 2.0)) why = "its lever fraction is not in (0, 2)";
      if (!why.empty())
        error->one(FLERR, "pair jgm: the restart file's contact of atoms {} and {} (types {} {}) is no history of "
                          "their law: {}", tag[i], tag[j], type[i], type[j], why);
    }
  }
}

void PairJGM::init_list(int id, NeighList *ptr)
{
  Pair::init_list(id, ptr);
  if (history) history->set_list(ptr);
}

double PairJGM::init_one(int i, int j)
{
  if (!mat_set[i] || !mat_set[j])
    error->all(FLERR, "pair_coeff jgm: no material for atom type {} (pair_coeff {} {} E nu Sy)",
               mat_set[i] ? j : i, mat_set[i] ? j : i, mat_set[i] ? j : i);
  if (onerad[i] > 0.0 && onerad[j] > 0.0) return onerad[i] + onerad[j];
  // a type with no atom and no inserting fix: the largest reach of any (compute() stops a run
  // where an atom is larger than its type's radius here)
  double most = 0.0;
  for (int t = 1; t <= atom->ntypes; ++t) most = std::max(most, onerad[t]);
  return 2.0 * most;
}

void PairJGM::build_laws()
{
  int n = atom->ntypes;
  // alone, every type needs a material; in pair_style hybrid only the types jgm serves (hybrid
  // calls init_one for each pair of types it maps here, and that names a type without one)
  const bool alone = force->pair == this;
  for (int t = 1; t <= n; ++t)
    if (!mat_set[t] && alone)
      error->all(FLERR, "pair_coeff jgm: no material for atom type {} (pair_coeff {} {} E nu Sy)", t, t, t);
  std::ostringstream key;
  key.precision(17);
  key << unloading_model;
  for (int t = 1; t <= n; ++t)
    key << ' ' << mat_set[t] << ' ' << mat[t].E << ' ' << mat[t].nu << ' ' << mat[t].Sy << ' ' << mat[t].Et;
  if (key.str() == laws_key) return;

  std::vector<FastrestJGM::LawRequest> req;
  law_of.assign((n + 1) * (n + 1), -1);
  for (int i = 1; i <= n; ++i)
    for (int j = i; j <= n; ++j) {
      if (!mat_set[i] || !mat_set[j]) continue;
      int found = -1;
      for (size_t k = 0; k < req.size() && found < 0; ++k)
        if (std::memcmp(&req[k].a, &mat[i], sizeof(Body)) == 0 && std::memcmp(&req[k].b, &mat[j], sizeof(Body)) == 0)
          found = static_cast<int>(k);
      if (found < 0) {
        found = static_cast<int>(req.size());
        req.push_back({false, mat[i], mat[j], fmt::format("types_{}_{}", i, j)});
      }
      law_of[i * (n + 1) + j] = law_of[j * (n + 1) + i] = found;
    }
  if (req.empty()) {    // hybrid with no type given a material here: nothing to build
    laws = FastrestJGM::Laws();
    laws_key = key.str();
    return;
  }
  FastrestJGM::request_laws(lmp, req, unloading_model, FastrestJGM::pascal_per_unit(update->unit_style), laws);
  laws_key = key.str();
}

// a x b
static inline void cross(const double *a, const double *b, double *c)
{
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

void PairJGM::compute(int eflag, int vflag)
{
  ev_init(eflag, vflag);
  double **x = atom->x, **v = atom->v, **f = atom->f, **omega = atom->omega, **torque = atom->torque;
  double *radius = atom->radius;
  int *type = atom->type;
  tagint *tag = atom->tag;
  int nlocal = atom->nlocal;
  int stride = atom->ntypes + 1;
  const double from_pressure = 1.0 / force->nktv2p, dt = update->dt;
  double dissipated = 0.0, stored = 0.0;
  // the forces of a run's set-up are those of the state as it is: histories advance only in steps
  // (a restarted run then repeats the uninterrupted one)
  const bool setup = update->setupflag != 0;
  if (setup && history->restored_rows) check_restored_rows();
  const int nh = nhist();
  const bool resist = model.res.any(), sliding = model.mu >= 0.0;
  double scratch[NHIST_ROLL];

  for (int ii = 0; ii < list->inum; ++ii) {
    int i = list->ilist[ii];
    double xi = x[i][0], yi = x[i][1], zi = x[i][2], ri = radius[i];
    // the neighbour cutoff was set for this type's largest radius: a larger atom could miss contacts
    if (ri > onerad[type[i]])
      error->one(FLERR, "pair jgm: atom {} (type {}) has radius {:.6g}, larger than the {:.6g} the neighbour cutoff "
                        "was set for at the run's start (the type's atoms then and the radii that fix pour or fix "
                        "deposit insert); start a new run after changing radii", tag[i], type[i], ri, onerad[type[i]]);
    int *jlist = list->firstneigh[i];
    double *rows_i = history->values(i);
    unsigned char *in_use = history->in_use(i);
    for (int jj = 0; jj < list->numneigh[i]; ++jj) {
      int j = jlist[jj] & NEIGHMASK;
      double dx = xi - x[j][0], dy = yi - x[j][1], dz = zi - x[j][2];
      double rsq = dx * dx + dy * dy + dz * dz;
      double radsum = ri + radius[j];
      if (rsq >= radsum * radsum && !in_use[jj]) continue;    // apart, no contact open: its row unread
      double *row = rows_i + static_cast<size_t>(jj) * nh, *h = row;
      if (setup) {
        for (int k = 0; k < nh; ++k) scratch[k] = row[k];
        h = scratch;
      }
      double weight = j < nlocal ? 1.0 : 0.5;    // a pair with a ghost is also stepped on its rank
      const FastrestJGM::Law &law = laws.law[law_of[type[i] * stride + type[j]]];
      double r = std::sqrt(rsq);
      double reff = ri * radius[j] / radsum;
      double w = (radsum - r) / (law.omega_c1 * reff);
      // an ended contact's energy is dissipated (half to each atom), and a later touch is a new contact
      if (FastrestJGM::contact_over(w, h)) {
        if (!setup) {
          history->ended(i) += 0.5 * h[H_W];
          if (j < nlocal) history->ended(j) += 0.5 * h[H_W];
        }
        for (int k = 0; k < nh; ++k) h[k] = 0.0;
        if (!setup) in_use[jj] = 0;
        continue;
      }
      double n[3] = {dx / r, dy / r, dz / r};
      // lever arms of the contact point, li + lj = r: torques then conserve angular momentum
      double q = r / radsum, li = ri * q, lj = radius[j] * q;
      double vt[3] = {0.0, 0.0, 0.0}, relrot[3] = {0.0, 0.0, 0.0};
      if (sliding) FastrestJGM::sliding_velocity(v[i], v[j], omega[i], omega[j], li, lj, n, vt);
      if (resist)
        for (int k = 0; k < 3; ++k) relrot[k] = omega[i][k] - omega[j][k];
      const FastrestJGM::ContactHistory hist = {h, h + H_XI, resist ? h + H_R : nullptr, resist ? h + H_T : nullptr};
      FastrestJGM::ContactForce cf;
      // set-up: the forces of the state as it is (dt 0), those of the step that left it
      if (!FastrestJGM::contact_step(model, laws, law, hist, w, reff, n, vt, relrot, from_pressure, setup ? 0.0 : dt,
                                     true, cf)) {
        if (w > law.w_end)
          error->one(FLERR, "pair jgm: atoms {} and {} (types {} {}) overlap past the model's end: w* = {:.6g} > {:.6g} "
                            "(interference {:.6g} of reduced radius {:.6g}): the impact is faster than the model "
                            "covers, or the time step too long for the contact",
                     tag[i], tag[j], type[i], type[j], w, law.w_end, radsum - r, reff);
        error->one(FLERR, "pair jgm: atoms {} and {} (types {} {}): no force at w* = {:.6g} (history lost)",
                   tag[i], tag[j], type[i], type[j], w);
      }
      // rolling and twisting torques: mt on i, -mt on j
      const double fn = cf.fn, *ft = cf.ft, *mt = cf.mt;
      double elastic = cf.elastic;
      double fv[3] = {fn * n[0] + ft[0], fn * n[1] + ft[1], fn * n[2] + ft[2]};
      double c[3], ti[3], tj[3];
      cross(n, ft, c);
      for (int k = 0; k < 3; ++k) {    // F_t at the contact point, -li n from i and +lj n from j
        ti[k] = -li * c[k] + mt[k];
        tj[k] = -lj * c[k] - mt[k];
      }
      // energy the contact takes from the atoms over the step: minus the trapezoid work of its
      // force and torques with the half-step velocities velocity Verlet moves the atoms by; summed
      // over contacts, the kinetic energy it gives them between force-free states, to rounding.
      // None at set-up: no step is taken there
      if (!setup) {
        double work = 0.0;
        for (int k = 0; k < 3; ++k) {
          double mi = resist ? h[H_M + k] : 0.0;    // the last step's rolling and twisting torque
          work += (h[H_F + k] + fv[k]) * (v[i][k] - v[j][k]) +
              (-ri * h[H_Q] * h[H_C + k] + mi + ti[k]) * omega[i][k] +
              (-radius[j] * h[H_Q] * h[H_C + k] - mi + tj[k]) * omega[j][k];
        }
        h[H_W] -= 0.5 * dt * work;
      }
      h[H_Q] = q;
      if (!setup) in_use[jj] = 1;
      for (int k = 0; k < 3; ++k) {
        h[H_F + k] = fv[k];
        h[H_C + k] = c[k];
      }
      if (resist)
        for (int k = 0; k < 3; ++k) h[H_M + k] = mt[k];
      dissipated += weight * (h[H_W] - elastic);
      stored += weight * elastic;
      for (int k = 0; k < 3; ++k) {
        f[i][k] += fv[k];
        torque[i][k] += ti[k];
      }
      if (j < nlocal)
        for (int k = 0; k < 3; ++k) {
          f[j][k] -= fv[k];
          torque[j][k] += tj[k];
        }
      if (evflag) ev_tally_xyz(i, j, nlocal, 0, elastic, 0.0, fv[0], fv[1], fv[2], dx, dy, dz);
    }
  }
  if (eflag_global) {    // compute pair reads pvector at steps that tally energy only
    double ended = 0.0;
    for (int i = 0; i < nlocal; ++i) ended += history->ended(i);
    pvector[0] = ended + dissipated;
    pvector[1] = stored;
  }
}

double PairJGM::contact_state(const double *h, const FastrestJGM::Law &law, double w, double reff, const double *n,
                              double &elastic, double *ft) const
{
  const double from_pressure = 1.0 / force->nktv2p;
  double copy[FastrestJGM::STATE] = {h[0], h[1], h[2], h[3]};
  double p = fastrest_law_step(laws.rows.data(), law.first, law.last, law.w_end, copy, w);
  double s = FastrestJGM::elastic_fraction(copy, w);
  elastic = FastrestJGM::normal_energy(copy, s, law, reff) * from_pressure;
  double fn = p * law.p_c1 * reff * reff * from_pressure;
  double along = h[H_F] * n[0] + h[H_F + 1] * n[1] + h[H_F + 2] * n[2];
  const double mu = model.mu;
  for (int k = 0; k < 3; ++k) ft[k] = mu >= 0.0 ? h[H_F + k] - along * n[k] : 0.0;
  double a = FastrestJGM::contact_radius(laws, law, copy, s, reff);
  double kt = FastrestJGM::tangential_stiffness(law, a) * from_pressure;
  if (mu >= 0.0 && kt > 0.0) elastic += 0.5 * (ft[0] * ft[0] + ft[1] * ft[1] + ft[2] * ft[2]) / kt;
  if (model.res.any()) elastic += FastrestJGM::resistance_energy(model.res, h + H_R, h[H_T], kt, a, mu);
  return fn;
}

// The history row of local atom i and atom j in the pair's list (under i, or under j if j is local:
// then its vectors are negated; single() reads magnitudes only), or nullptr
const double *PairJGM::row_of(int i, int j)
{
  if (!list || !history || i >= atom->nlocal) return nullptr;
  for (int side = 0; side < 2; ++side) {
    int a = side == 0 ? i : j, b = side == 0 ? j : i;
    if (a >= atom->nlocal) break;
    int num = list->numneigh[a], *jlist = list->firstneigh[a];
    for (int jj = 0; jj < num; ++jj)
      if ((jlist[jj] & NEIGHMASK) == b) return history->values(a) + static_cast<size_t>(jj) * nhist();
  }
  return nullptr;
}

// compute pair/local: fforce (the force on i is fforce (x_i - x_j)), the elastic energy held, and
// svector (see NSINGLE); zeros for two atoms not in contact
double PairJGM::single(int i, int j, int itype, int jtype, double rsq, double, double, double &fforce)
{
  fforce = 0.0;
  for (int k = 0; k < NSINGLE; ++k) svector[k] = 0.0;
  const double *h = row_of(i, j);
  double *radius = atom->radius;
  double radsum = radius[i] + radius[j];
  if (!h || (rsq >= radsum * radsum && !(h[0] > 0.0)) || rsq <= 0.0) return 0.0;
  const FastrestJGM::Law &law = laws.law[law_of[itype * (atom->ntypes + 1) + jtype]];
  double r = std::sqrt(rsq), reff = radius[i] * radius[j] / radsum;
  double w = (radsum - r) / (law.omega_c1 * reff);
  if (FastrestJGM::contact_over(w, h)) return 0.0;
  double **x = atom->x;
  double n[3] = {(x[i][0] - x[j][0]) / r, (x[i][1] - x[j][1]) / r, (x[i][2] - x[j][2]) / r};
  double elastic, ft[3];
  double fn = contact_state(h, law, w, reff, n, elastic, ft);
  fforce = fn / r;
  svector[0] = fn;
  svector[1] = std::sqrt(ft[0] * ft[0] + ft[1] * ft[1] + ft[2] * ft[2]);
  svector[2] = w;
  svector[3] = h[0];
  svector[4] = h[H_W] - elastic;
  svector[5] = FastrestJGM::contact_radius(laws, law, h, FastrestJGM::elastic_fraction(h, w), reff);
  svector[6] = elastic;
  return elastic;
}

void PairJGM::per_atom(double **out)
{
  int nlocal = atom->nlocal, stride = atom->ntypes + 1;
  double **x = atom->x, *radius = atom->radius;
  int *type = atom->type;
  for (int i = 0; i < nlocal; ++i) {
    out[i][0] = history ? history->ended(i) : 0.0;
    out[i][1] = out[i][2] = 0.0;
  }
  if (!list || !history) return;
  const int nh = nhist();
  for (int ii = 0; ii < list->inum; ++ii) {
    int i = list->ilist[ii];
    int *jlist = list->firstneigh[i];
    const double *h = history->values(i);
    for (int jj = 0; jj < list->numneigh[i]; ++jj, h += nh) {
      if (!(h[0] > 0.0)) continue;
      int j = jlist[jj] & NEIGHMASK;
      double dx = x[i][0] - x[j][0], dy = x[i][1] - x[j][1], dz = x[i][2] - x[j][2];
      double r = std::sqrt(dx * dx + dy * dy + dz * dz), radsum = radius[i] + radius[j];
      const FastrestJGM::Law &law = laws.law[law_of[type[i] * stride + type[j]]];
      double reff = radius[i] * radius[j] / radsum;
      double w = (radsum - r) / (law.omega_c1 * reff);
      if (FastrestJGM::contact_over(w, h) || !(r > 0.0)) continue;
      double n[3] = {dx / r, dy / r, dz / r}, elastic, ft[3];
      contact_state(h, law, w, reff, n, elastic, ft);
      for (int a : {i, j}) {
        if (a >= nlocal) continue;
        out[a][0] += 0.5 * (h[H_W] - elastic);
        out[a][1] += 0.5 * elastic;
        out[a][2] += 1.0;
      }
    }
  }
}
