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
    Pair(lmp), unloading_model("jcg"), mu(-1.0), maxrad(0.0), ended(0.0), history(nullptr)
{
  nextra = 2;    // compute pair jgm: [1] energy dissipated in contacts, [2] elastic energy they hold
  pvector = new double[2];
  pvector[0] = pvector[1] = 0.0;
  single_enable = 0;
  restartinfo = 0;    // pair_style and pair_coeff are given again after read_restart
  finitecutflag = 1;
  no_virial_fdotr_compute = 1;    // forces on ghosts stay 0 (newton-off list): sum pair by pair
}

PairJGM::~PairJGM()
{
  delete[] pvector;
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
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) setflag[i][j] = 0;
  mat.assign(n, Body{0.0, 0.0, 0.0, 0.0});
  mat_set.assign(n, 0);
}

void PairJGM::settings(int narg, char **arg)
{
  unloading_model = "jcg";
  mu = -1.0;
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
    } else {
      error->all(FLERR, "pair_style jgm: unknown keyword '{}' (expected unloading or tangential)", key);
    }
  }
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
      setflag[i][i] = 1;
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
  neighbor->add_request(this, NeighConst::REQ_SIZE | NeighConst::REQ_NEWTON_OFF);

  Fix *f = modify->get_fix_by_id(HISTORY_ID);
  // ghost atoms carry velocities (comm_modify vel yes): a contact's first step of work needs them;
  // set before comm->init() sizes the messages
  comm->ghost_velocity = 1;
  if (!f) f = modify->add_fix(fmt::format("{} all jgm/history {} {} {}", HISTORY_ID, NHIST, H_F, NHIST));
  history = dynamic_cast<FixJGMHistory *>(f);
  if (!history) error->all(FLERR, "fix ID {} is reserved for pair_style jgm", HISTORY_ID);

  double local = 0.0;
  for (int i = 0; i < atom->nlocal; ++i) local = std::max(local, atom->radius[i]);
  MPI_Allreduce(&local, &maxrad, 1, MPI_DOUBLE, MPI_MAX, world);
  build_laws();
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
  return maxrad > 0.0 ? 2.0 * maxrad : 1.0;
}

void PairJGM::build_laws()
{
  int n = atom->ntypes;
  for (int t = 1; t <= n; ++t)
    if (!mat_set[t])
      error->all(FLERR, "pair_coeff jgm: no material for atom type {} (pair_coeff {} {} E nu Sy)", t, t, t);
  std::ostringstream key;
  key.precision(17);
  key << unloading_model;
  for (int t = 1; t <= n; ++t) key << ' ' << mat[t].E << ' ' << mat[t].nu << ' ' << mat[t].Sy << ' ' << mat[t].Et;
  if (key.str() == laws_key) return;

  std::vector<FastrestJGM::LawRequest> req;
  law_of.assign((n + 1) * (n + 1), -1);
  for (int i = 1; i <= n; ++i)
    for (int j = i; j <= n; ++j) {
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
  FastrestJGM::request_laws(lmp, req, unloading_model, laws);
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
  const double *rows = laws.rows.data();
  const double from_pressure = 1.0 / force->nktv2p, dt = update->dt;
  double dissipated = 0.0, stored = 0.0;
  // the forces of a run's set-up are those of the state as it is: histories advance only in steps
  // (a restarted run then repeats the uninterrupted one)
  const bool setup = update->setupflag != 0;
  double scratch[NHIST];

  for (int ii = 0; ii < list->inum; ++ii) {
    int i = list->ilist[ii];
    double xi = x[i][0], yi = x[i][1], zi = x[i][2], ri = radius[i];
    int *jlist = list->firstneigh[i];
    double *row = history->values(i);
    for (int jj = 0; jj < list->numneigh[i]; ++jj, row += NHIST) {
      double *h = row;
      if (setup) {
        for (int k = 0; k < NHIST; ++k) scratch[k] = row[k];
        h = scratch;
      }
      int j = jlist[jj] & NEIGHMASK;
      double weight = j < nlocal ? 1.0 : 0.5;    // a pair with a ghost is also stepped on its rank
      double dx = xi - x[j][0], dy = yi - x[j][1], dz = zi - x[j][2];
      double rsq = dx * dx + dy * dy + dz * dz;
      double radsum = ri + radius[j];
      if (rsq >= radsum * radsum && !(h[0] > 0.0)) continue;    // apart, no contact open
      const FastrestJGM::Law &law = laws.law[law_of[type[i] * stride + type[j]]];
      double r = std::sqrt(rsq);
      double reff = ri * radius[j] / radsum;
      double w = (radsum - r) / (law.omega_c1 * reff);
      // an ended contact's energy is dissipated, and a later touch is a new contact
      if (FastrestJGM::contact_over(w, h)) {
        if (!setup) ended += weight * h[H_W];
        for (int k = 0; k < NHIST; ++k) h[k] = 0.0;
        continue;
      }
      double p = fastrest_law_step(rows, law.first, law.last, law.w_end, h, w);
      if (!(p == p)) {
        if (w > law.w_end)
          error->one(FLERR, "pair jgm: atoms {} and {} (types {} {}) overlap past the model's end: w* = {:.6g} > {:.6g} "
                            "(interference {:.6g} of reduced radius {:.6g}); lower the impact speed or the time step",
                     tag[i], tag[j], type[i], type[j], w, law.w_end, radsum - r, reff);
        error->one(FLERR, "pair jgm: atoms {} and {} (types {} {}): no force at w* = {:.6g} (history lost)",
                   tag[i], tag[j], type[i], type[j], w);
      }
      double fn = p * law.p_c1 * reff * reff * from_pressure;
      double n[3] = {dx / r, dy / r, dz / r};
      // elastic energy of the normal law: the integral of its unloading branch, JGM eq (32)
      double s = FastrestJGM::elastic_fraction(h, w);
      double elastic = 0.4 * h[1] * h[3] * s * s * std::sqrt(s) * law.p_c1 * law.omega_c1 * reff * reff * reff *
          from_pressure;
      double ft[3] = {0.0, 0.0, 0.0};
      // lever arms of the contact point, li + lj = r: torques then conserve angular momentum
      double q = r / radsum, li = ri * q, lj = radius[j] * q;
      if (mu >= 0.0) {
        double kt = FastrestJGM::mindlin_stiffness(laws, law, h, s, reff) * from_pressure;
        double spin[3] = {li * omega[i][0] + lj * omega[j][0], li * omega[i][1] + lj * omega[j][1],
                          li * omega[i][2] + lj * omega[j][2]};
        double turn[3];
        cross(spin, n, turn);
        double vt[3] = {v[i][0] - v[j][0] - turn[0], v[i][1] - v[j][1] - turn[1], v[i][2] - v[j][2] - turn[2]};
        // set-up: the force of the displacement as it is (dt 0), that of the step that left it
        elastic += FastrestJGM::mindlin_step(h + H_XI, n, vt, kt, mu * fn, setup ? 0.0 : dt, ft);
      }
      double fv[3] = {fn * n[0] + ft[0], fn * n[1] + ft[1], fn * n[2] + ft[2]};
      double c[3], ti[3], tj[3];
      cross(n, ft, c);
      for (int k = 0; k < 3; ++k) {    // F_t at the contact point, -li n from i and +lj n from j
        ti[k] = -li * c[k];
        tj[k] = -lj * c[k];
      }
      // energy the contact takes from the atoms over the step: minus the trapezoid work of its
      // force and torques with the half-step velocities velocity Verlet moves the atoms by; summed
      // over contacts, the kinetic energy it gives them between force-free states, to rounding
      double work = 0.0;
      for (int k = 0; k < 3; ++k)
        work += (h[H_F + k] + fv[k]) * (v[i][k] - v[j][k]) - (ri * h[H_Q] * h[H_C + k] - ti[k]) * omega[i][k] -
            (radius[j] * h[H_Q] * h[H_C + k] - tj[k]) * omega[j][k];
      h[H_W] -= 0.5 * dt * work;
      h[H_Q] = q;
      for (int k = 0; k < 3; ++k) {
        h[H_F + k] = fv[k];
        h[H_C + k] = c[k];
      }
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
  pvector[0] = ended + dissipated;
  pvector[1] = stored;
}
