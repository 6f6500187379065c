#include "fix_wall_jgm.h"

#include "pair_jgm.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "force.h"
#include "memory.h"
#include "update.h"

#include "fastrest_law.h"
#include "jgm_tangential.h"

#include <cmath>
#include <cstring>
#include <mpi.h>
#include <sstream>

using namespace LAMMPS_NS;
using namespace FixConst;

static const char *WHERE = "fix wall/jgm";

// fix ID group wall/jgm zplane ZLO ZHI E nu Sy [Et value] [unloading jcg|etsion|brake]
//     [tangential none|mindlin MU]
FixWallJGM::FixWallJGM(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), zlo(0.0), zhi(0.0), has_lo(0), has_hi(0), mu_own(-1.0), mu_given(false), restored(false),
    hist(nullptr), force_flag(0)
{
  if (narg < 9)
    error->all(FLERR, "fix wall/jgm: expected 'zplane ZLO ZHI E nu Sy [Et value] [unloading MODEL]', got {} arguments",
               narg - 3);
  if (std::strcmp(arg[3], "zplane") != 0)
    error->all(FLERR, "fix wall/jgm: wall '{}' is not supported (only zplane)", arg[3]);
  if (std::strcmp(arg[4], "NULL") != 0) { zlo = FastrestJGM::finite_number(lmp, WHERE, "ZLO", arg[4]); has_lo = 1; }
  if (std::strcmp(arg[5], "NULL") != 0) { zhi = FastrestJGM::finite_number(lmp, WHERE, "ZHI", arg[5]); has_hi = 1; }
  if (!has_lo && !has_hi) error->all(FLERR, "fix wall/jgm: ZLO and ZHI are both NULL");
  if (has_lo && has_hi && !(zlo < zhi)) error->all(FLERR, "fix wall/jgm: ZLO = {} must be < ZHI = {}", zlo, zhi);
  const char *et = nullptr;
  unloading = "";
  int k = 9;
  while (k < narg) {
    if (k + 1 >= narg) error->all(FLERR, "fix wall/jgm: keyword '{}' needs a value", arg[k]);
    if (std::strcmp(arg[k], "tangential") == 0) {
      mu_given = true;
      if (std::strcmp(arg[k + 1], "none") == 0) {
        mu_own = -1.0;
      } else if (std::strcmp(arg[k + 1], "mindlin") == 0) {
        if (k + 2 >= narg) error->all(FLERR, "fix wall/jgm: 'tangential mindlin' needs the friction coefficient MU");
        mu_own = FastrestJGM::finite_number(lmp, WHERE, "MU", arg[k + 2]);
        if (!(mu_own >= 0.0)) error->all(FLERR, "fix wall/jgm: friction coefficient MU = {} must be >= 0", arg[k + 2]);
        ++k;
      } else {
        error->all(FLERR, "fix wall/jgm: tangential model '{}' is not none or mindlin", arg[k + 1]);
      }
    } else if (std::strcmp(arg[k], "Et") == 0) et = arg[k + 1];
    else if (std::strcmp(arg[k], "unloading") == 0) {
      unloading = arg[k + 1];
      if (unloading != "jcg" && unloading != "etsion" && unloading != "brake")
        error->all(FLERR, "fix wall/jgm: unloading model '{}' is not one of jcg, etsion, brake", unloading);
    } else error->all(FLERR, "fix wall/jgm: unknown keyword '{}' (expected Et, unloading or tangential)", arg[k]);
    k += 2;
  }
  wall = FastrestJGM::read_body(lmp, WHERE, arg[6], arg[7], arg[8], et);
  if (!atom->radius_flag || !atom->omega_flag || !atom->torque_flag)
    error->all(FLERR, "fix wall/jgm needs per-atom radius, omega and torque (atom_style sphere)");

  vector_flag = 1;
  size_vector = 2;
  global_freq = 1;
  extvector = 1;
  restart_global = 1;
  restart_peratom = 1;
  create_attribute = 1;
  maxexchange = NV;
  wall_force[0] = wall_force[1] = 0.0;
  grow_arrays(atom->nmax);
  atom->add_callback(Atom::GROW);
  atom->add_callback(Atom::RESTART);
  for (int i = 0; i < atom->nlocal; ++i) set_arrays(i);
}

FixWallJGM::~FixWallJGM()
{
  atom->delete_callback(id, Atom::GROW);
  atom->delete_callback(id, Atom::RESTART);
  memory->destroy(hist);
}

int FixWallJGM::setmask() { return POST_FORCE; }

void FixWallJGM::init()
{
  auto *pair = dynamic_cast<PairJGM *>(force->pair_match("jgm", 1));
  if (!pair) error->all(FLERR, "fix wall/jgm needs pair_style jgm (the particles' materials)");
  std::string model = unloading.empty() ? pair->unloading() : unloading;
  contact = pair->contact_model();    // the pair style's tangential model, rolling and twisting
  if (mu_given) contact.mu = mu_own;   // unless the wall is given its own friction
  if (contact.res.twist == FastrestJGM::Resistance::MARSHALL && contact.mu < 0.0)
    error->all(FLERR, "fix wall/jgm: the pair style's 'twisting marshall' needs the wall's tangential mindlin MU, "
                      "but the wall has 'tangential none'");
  if (!restored_wall.empty()) {
    const std::vector<double> &o = restored_wall;
    bool open = false;
    for (int i = 0; i < atom->nlocal && !open; ++i) open = FastrestJGM::row_open(hist[i], NV);
    int any = 0, mine = open;
    MPI_Allreduce(&mine, &any, 1, MPI_INT, MPI_MAX, world);
    if (any && (o[0] != wall.E || o[1] != wall.nu || o[2] != wall.Sy || o[3] != wall.Et ||
                o[4] != FastrestJGM::unloading_index(model)))
      error->all(FLERR, "fix wall/jgm: the restart file's open wall contacts are of a wall with E {:.17g} nu {:.17g} "
                        "Sy {:.17g} Et {:.17g} and unloading {}; give the same wall (or continue from a data file, "
                        "where contacts start anew)", o[0], o[1], o[2], o[3], static_cast<int>(o[4]));
    restored_wall.clear();
  }
  int n = atom->ntypes;
  std::vector<FastrestJGM::LawRequest> req;
  std::ostringstream key;
  key.precision(17);
  key << model;
  law_of.assign(n + 1, -1);
  model_code = FastrestJGM::unloading_index(model);
  for (int t = 1; t <= n; ++t) {
    const FastrestJGM::Body *b = pair->material(t);
    if (!b) error->all(FLERR, "fix wall/jgm: no material for atom type {} (pair_coeff {} {} E nu Sy)", t, t, t);
    key << ' ' << b->E << ' ' << b->nu << ' ' << b->Sy << ' ' << b->Et;
    law_of[t] = static_cast<int>(req.size());
    req.push_back({true, *b, wall, fmt::format("type_{}_on_wall_{}", t, id)});
  }
  if (key.str() != laws_key) {
    FastrestJGM::request_laws(lmp, req, model, FastrestJGM::pascal_per_unit(update->unit_style), laws);
    laws_key = key.str();
  }
}

void FixWallJGM::setup(int vflag)
{
  if (restored) {    // every history read back is one its law can have written
    restored = false;
    for (int i = 0; i < atom->nlocal; ++i)
      for (int side = 0; side < 2; ++side) {
        const double *h = hist[i] + side * PER_WALL;
        if (!FastrestJGM::row_open(h, PER_WALL)) continue;
        std::string why = FastrestJGM::row_problem(laws, law_of[atom->type[i]], h);
        for (int k = FastrestJGM::STATE; k < PER_WALL && why.empty(); ++k)
          if (!std::isfinite(h[k])) why = "a tangential, rolling or twisting value is not finite";
        if (!why.empty())
          error->one(FLERR, "fix wall/jgm: the restart file's contact of atom {} with the {} wall is no history of "
                            "its law: {}", atom->tag[i], side == 0 ? "lower" : "upper", why);
      }
  }
  post_force(vflag);
}

void FixWallJGM::write_restart(FILE *fp)
{
  if (comm->me != 0) return;
  double rec[6] = {5.0, wall.E, wall.nu, wall.Sy, wall.Et, static_cast<double>(model_code)};
  int size = sizeof(rec);
  fwrite(&size, sizeof(int), 1, fp);
  fwrite(rec, sizeof(double), 6, fp);
}

void FixWallJGM::restart(char *buf)
{
  double rec[6];
  std::memcpy(rec, buf, sizeof(rec));
  bool ok = rec[0] == 5.0;
  for (double v : rec) ok = ok && std::isfinite(v);
  if (!ok) error->all(FLERR, "fix wall/jgm: the restart file's record of the wall is damaged");
  restored_wall.assign(rec + 1, rec + 6);
}

void FixWallJGM::post_force(int)
{
  double **x = atom->x, **v = atom->v, **f = atom->f, **omega = atom->omega, **torque = atom->torque;
  double *radius = atom->radius;
  int *mask = atom->mask, *type = atom->type;
  const double from_pressure = 1.0 / force->nktv2p, dt = update->dt;
  const bool resist = contact.res.any(), sliding = contact.mu >= 0.0;
  const double still[3] = {0.0, 0.0, 0.0};    // the wall: a body at rest
  force_flag = 0;
  wall_force[0] = wall_force[1] = 0.0;
  for (int i = 0; i < atom->nlocal; ++i) {
    if (!(mask[i] & groupbit)) continue;
    const FastrestJGM::Law &law = laws.law[law_of[type[i]]];
    double r = radius[i];
    for (int side = 0; side < 2; ++side) {
      if (side == 0 ? !has_lo : !has_hi) continue;
      double gap = side == 0 ? x[i][2] - zlo : zhi - x[i][2];
      double *h = hist[i] + side * PER_WALL, scratch[PER_WALL];
      if (update->setupflag) {    // set-up forces leave the history as it is (see pair_jgm.cpp)
        for (int k = 0; k < PER_WALL; ++k) scratch[k] = h[k];
        h = scratch;
      }
      if (gap >= r && !(h[0] > 0.0)) continue;
      double w = (r - gap) / (law.omega_c1 * r);
      if (FastrestJGM::contact_over(w, h)) {
        for (int k = 0; k < PER_WALL; ++k) h[k] = 0.0;
        continue;
      }
      double n[3] = {0.0, 0.0, side == 0 ? 1.0 : -1.0};    // from the wall to the sphere
      // as pair_style jgm, with the wall a body at rest and the sphere's radius the reduced one
      double vt[3] = {0.0, 0.0, 0.0};
      if (sliding) FastrestJGM::sliding_velocity(v[i], still, omega[i], still, r, 0.0, n, vt);
      const FastrestJGM::ContactHistory ch = {h, h + W_XI, h + W_R, h + W_T};
      FastrestJGM::ContactForce cf;
      if (!FastrestJGM::contact_step(contact, laws, law, ch, w, r, n, vt, omega[i], from_pressure,
                                     update->setupflag ? 0.0 : dt, false, cf))
        error->one(FLERR, "fix wall/jgm: atom {} (type {}) overlaps the {} wall past the model's end: w* = {:.6g} > {:.6g}",
                   atom->tag[i], type[i], side == 0 ? "lower" : "upper", w, law.w_end);
      const double fn = cf.fn, *ft = cf.ft;
      if (resist)
        for (int k = 0; k < 3; ++k) torque[i][k] += cf.mt[k];
      if (sliding) {    // torque of F_t applied at -r n: (-r n) x F_t
        torque[i][0] += -r * (n[1] * ft[2] - n[2] * ft[1]);
        torque[i][1] += -r * (n[2] * ft[0] - n[0] * ft[2]);
        torque[i][2] += -r * (n[0] * ft[1] - n[1] * ft[0]);
      }
      for (int k = 0; k < 3; ++k) f[i][k] += fn * n[k] + ft[k];
      wall_force[side] -= fn * n[2];
    }
  }
}

double FixWallJGM::compute_vector(int n)
{
  if (force_flag == 0) {
    MPI_Allreduce(wall_force, wall_force_all, 2, MPI_DOUBLE, MPI_SUM, world);
    force_flag = 1;
  }
  return wall_force_all[n];
}

void FixWallJGM::grow_arrays(int nmax) { memory->grow(hist, nmax, NV, "wall/jgm:hist"); }

void FixWallJGM::copy_arrays(int i, int j, int)
{
  for (int k = 0; k < NV; ++k) hist[j][k] = hist[i][k];
}

void FixWallJGM::set_arrays(int i)
{
  for (int k = 0; k < NV; ++k) hist[i][k] = 0.0;
}

int FixWallJGM::pack_exchange(int i, double *buf)
{
  for (int k = 0; k < NV; ++k) buf[k] = hist[i][k];
  return NV;
}

int FixWallJGM::unpack_exchange(int nlocal, double *buf)
{
  for (int k = 0; k < NV; ++k) hist[nlocal][k] = buf[k];
  return NV;
}

int FixWallJGM::pack_restart(int i, double *buf)
{
  buf[0] = NV + 1;
  for (int k = 0; k < NV; ++k) buf[1 + k] = hist[i][k];
  return NV + 1;
}

void FixWallJGM::unpack_restart(int nlocal, int nth)
{
  double **extra = atom->extra;
  int m = FastrestJGM::restart_record(extra[nlocal], atom->nextra_store, nth);
  if (m < 0) error->one(FLERR, "fix wall/jgm: restart file holds a damaged record for atom {}", atom->tag[nlocal]);
  if (m + NV + 1 > atom->nextra_store || extra[nlocal][m] != NV + 1)
    error->one(FLERR, "fix wall/jgm: restart file holds a bad history for atom {}", atom->tag[nlocal]);
  for (int k = 0; k < NV; ++k) hist[nlocal][k] = extra[nlocal][m + 1 + k];
  restored = restored || FastrestJGM::row_open(hist[nlocal], NV);
}

int FixWallJGM::size_restart(int) { return NV + 1; }

int FixWallJGM::maxsize_restart() { return NV + 1; }

double FixWallJGM::memory_usage() { return static_cast<double>(atom->nmax) * NV * sizeof(double); }
