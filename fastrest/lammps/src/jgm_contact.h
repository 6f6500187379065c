/* One step of a JGM contact, shared by pair_style jgm and fix wall/jgm (as LAMMPS's GranularModel
   serves pair granular and fix wall/gran): the normal law, Mindlin friction, rolling and twisting
   resistance, on histories the caller keeps. The caller brings the geometry (w*, the reduced
   radius, the normal, the contact point's sliding velocity, the relative spin) and applies the
   forces and torques to its bodies. */
#ifndef FASTREST_JGM_CONTACT_H
#define FASTREST_JGM_CONTACT_H

#include "fastrest_law.h"
#include "jgm_laws.h"
#include "jgm_tangential.h"

namespace FastrestJGM {

//! The tangential and resistance models of a contact (pair_style jgm's keywords; the wall's
//! follow them unless it is given its own friction).
struct ContactModel {
  double mu = -1.0;    // Coulomb friction coefficient of tangential mindlin; < 0: tangential none
  Resistance res;      // rolling and twisting
};

//! Where a contact keeps its histories: the law's row (STATE values); the tangential displacement
//! (3 values, with friction); the rolling displacement (3) and twist angle (with resistance).
struct ContactHistory {
  double *state, *xi, *roll, *twist;
};

//! One step's result: normal force fn (force units); tangential force ft and rolling and twisting
//! torque mt on this body (minus them on the other); elastic energy the contact holds.
struct ContactForce {
  double fn, ft[3], mt[3], elastic;
};

/* One step at w* of a contact of reduced radius reff (a sphere's own radius on a wall): n from the
   other body to this one, vt the sliding velocity of the contact point (this body's minus the
   other's), relrot this body's spin minus the other's; dt 0 at a run's set-up (forces of the state
   as it is). energy: whether the elastic energy includes the normal law's (JGM eq 32; friction's
   and resistance's are always in). Returns false where the law has no force (w* past its end, or
   a lost history): out is then unset. */
inline bool contact_step(const ContactModel &model, const Laws &laws, const Law &law, const ContactHistory &h,
                         double w, double reff, const double *n, const double *vt, const double *relrot,
                         double from_pressure, double dt, bool energy, ContactForce &out)
{
  double p = fastrest_law_step(laws.rows.data(), law.first, law.last, law.w_end, h.state, w);
  if (!(p == p)) return false;
  out.fn = p * law.p_c1 * reff * reff * from_pressure;
  double s = elastic_fraction(h.state, w);
  out.elastic = energy ? normal_energy(h.state, s, law, reff) * from_pressure : 0.0;
  for (int k = 0; k < 3; ++k) out.ft[k] = out.mt[k] = 0.0;
  const bool resist = model.res.any();
  // one contact radius serves Mindlin's k_t = 8 G* a and rolling and twisting
  double a = (model.mu >= 0.0 || resist) ? contact_radius(laws, law, h.state, s, reff) : 0.0;
  double kt = tangential_stiffness(law, a) * from_pressure;
  if (model.mu >= 0.0) out.elastic += mindlin_step(h.xi, n, vt, kt, model.mu * out.fn, dt, out.ft);
  if (resist)
    out.elastic += resistance_step(model.res, h.roll, h.twist, relrot, n, reff, out.fn, kt, a, model.mu, dt, out.mt);
  return true;
}

/* The sliding velocity of the contact point of bodies i and j (v, omega each) touching along n
   (from j to i) at lever arms li from i and lj from j: v_i - v_j - (li omega_i + lj omega_j) x n.
   A wall is a body at rest with lever arm 0. */
inline void sliding_velocity(const double *vi, const double *vj, const double *wi, const double *wj, double li,
                             double lj, const double *n, double *vt)
{
  double spin[3] = {li * wi[0] + lj * wj[0], li * wi[1] + lj * wj[1], li * wi[2] + lj * wj[2]};
  vt[0] = vi[0] - vj[0] - (spin[1] * n[2] - spin[2] * n[1]);
  vt[1] = vi[1] - vj[1] - (spin[2] * n[0] - spin[0] * n[2]);
  vt[2] = vi[2] - vj[2] - (spin[0] * n[1] - spin[1] * n[0]);
}

}    // namespace FastrestJGM

#endif
