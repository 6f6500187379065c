/* Tangential force of a contact: Mindlin-Deresiewicz no-slip stiffness k_t = 8 G* a on the contact
   radius a of the normal law, the tangential displacement as history, Coulomb's limit mu F_n.

   The form of LAMMPS's granular "mindlin" (Mindlin 1949; Mindlin & Deresiewicz 1953 for the
   stiffness, Thornton et al. 2013 for its use in DEM): the displacement xi, rotated into the
   current tangent plane at its length, grows by the sliding velocity of the contact point times
   dt; F_t = -k_t xi, capped at mu F_n, where xi is set back to -F_t/k_t (sliding). */
#ifndef FASTREST_JGM_TANGENTIAL_H
#define FASTREST_JGM_TANGENTIAL_H

#include "fastrest_law.h"
#include "jgm_laws.h"

#include <cmath>

namespace FastrestJGM {

/* Contact radius a (length) of a contact with history row `state` at elastic fraction s
   (elastic_fraction), reduced radius reff: a^2 = a_c^2 A*(w_max) s, A* from the law's area cells
   (Hertz's a^2 proportional to the interference from w_res* on the branch). */
inline double contact_radius(const Laws &laws, const Law &law, const double *state, double s, double reff)
{
  double wm = state[0];
  if (!(wm > 0.0)) return 0.0;
  const double *ar = laws.area.data() + LawFile::AREA_ROW * fastrest_law_row(wm, law.first, law.last);
  double a_star = fastrest_law_estrin5((wm - ar[0]) * ar[1], ar[2], ar[3], ar[4], ar[5], ar[6], ar[7]) * s;
  return law.a_c1 * reff * std::sqrt(a_star > 0.0 ? a_star : 0.0);
}

//! Mindlin's no-slip stiffness k_t = 8 G* a (pressure x length) on contact radius a.
inline double tangential_stiffness(const Law &law, double a) { return 8.0 * law.g_eff * a; }

/* n: unit normal (from the other body to this one); vt: sliding velocity of the contact point
   (this body's minus the other's, any normal part is removed); xi: the displacement, updated;
   ft: the tangential force on this body. Returns the elastic energy 0.5 |F_t|^2 / k_t held. */
inline double mindlin_step(double *xi, const double *n, const double *vt, double kt, double limit, double dt,
                           double *ft)
{
  double old = std::sqrt(xi[0] * xi[0] + xi[1] * xi[1] + xi[2] * xi[2]);
  double xn = xi[0] * n[0] + xi[1] * n[1] + xi[2] * n[2];
  for (int k = 0; k < 3; ++k) xi[k] -= xn * n[k];
  double now = std::sqrt(xi[0] * xi[0] + xi[1] * xi[1] + xi[2] * xi[2]);
  double scale = now > 0.0 ? old / now : 0.0;
  double vn = vt[0] * n[0] + vt[1] * n[1] + vt[2] * n[2];
  for (int k = 0; k < 3; ++k) xi[k] = xi[k] * scale + (vt[k] - vn * n[k]) * dt;
  if (!(kt > 0.0)) {    // no contact area (apart in the normal law): no tangential force
    for (int k = 0; k < 3; ++k) xi[k] = ft[k] = 0.0;
    return 0.0;
  }
  for (int k = 0; k < 3; ++k) ft[k] = -kt * xi[k];
  double f = std::sqrt(ft[0] * ft[0] + ft[1] * ft[1] + ft[2] * ft[2]);
  if (f > limit) {    // sliding
    double c = limit / f;
    for (int k = 0; k < 3; ++k) {
      ft[k] *= c;
      xi[k] = -ft[k] / kt;
    }
    f = limit;
  }
  return 0.5 * f * f / kt;
}


/* Rolling resistance, LAMMPS granular's "rolling sds K GAMMA MU" (spring-dashpot-slider; Luding
   2008, Wang et al. 2015 for the rolling velocity): the rolling displacement xi (history, turned into
   the tangent plane at its length) grows by the rolling velocity vrl = R' (omega_i - omega_j) x n
   times dt; the rolling "force" F_r = -K xi - GAMMA vrl, capped at MU F_n (xi then set back to
   what gives the cap), acts as the torque R' n x F_r on this body (minus it on the other). Returns
   the elastic energy 0.5 K |xi|^2 held. */
inline double rolling_step(double *xi, const double *n, const double *vrl, double k, double gamma, double limit,
                           double dt, double *fr)
{
  double old = std::sqrt(xi[0] * xi[0] + xi[1] * xi[1] + xi[2] * xi[2]);
  double xn = xi[0] * n[0] + xi[1] * n[1] + xi[2] * n[2];
  for (int m = 0; m < 3; ++m) xi[m] -= xn * n[m];
  double now = std::sqrt(xi[0] * xi[0] + xi[1] * xi[1] + xi[2] * xi[2]);
  double scale = now > 0.0 ? old / now : 0.0;
  for (int m = 0; m < 3; ++m) {
    xi[m] = xi[m] * scale + vrl[m] * dt;
    fr[m] = -k * xi[m] - gamma * vrl[m];
  }
  double f = std::sqrt(fr[0] * fr[0] + fr[1] * fr[1] + fr[2] * fr[2]);
  if (f > limit) {    // rolling: the slider
    double c = limit / f;
    for (int m = 0; m < 3; ++m) {
      fr[m] *= c;
      xi[m] = k > 0.0 ? -(fr[m] + gamma * vrl[m]) / k : 0.0;
    }
  }
  return 0.5 * k * (xi[0] * xi[0] + xi[1] * xi[1] + xi[2] * xi[2]);
}

/* Twisting resistance about the normal: the twist angle theta (history) grows by the relative spin
   about n, omega_n = (omega_i - omega_j) . n, times dt; the torque M = -K theta - GAMMA omega_n
   (along n on this body, minus it on the other), capped at `limit` (theta then set back to what
   gives the cap). LAMMPS's "twisting sds K GAMMA MU": limit MU F_n; "twisting marshall" (Marshall
   2009, eqs 30-34): K = k_t a^2/2 of the contact's tangential stiffness k_t and radius a, GAMMA 0,
   limit (2/3) mu a F_n. Returns the elastic energy 0.5 K theta^2 held. */
inline double twisting_step(double *theta, double spin, double k, double gamma, double limit, double dt,
                            double *torque)
{
  *theta += spin * dt;
  double m = -k * *theta - gamma * spin;
  if (std::fabs(m) > limit) {    // twisting: the slider, turning the way the spring pulls
    m = m > 0.0 ? limit : -limit;
    *theta = k > 0.0 ? -(m + gamma * spin) / k : 0.0;
  }
  *torque = m;
  return 0.5 * k * *theta * *theta;
}

struct Resistance;
//! Read "rolling none|sds K GAMMA MU" or "twisting none|marshall|sds K GAMMA MU" at arg[k]; returns
//! the index after it (LAMMPS errors name what is wrong).
int read_resistance(LAMMPS_NS::LAMMPS *lmp, const std::string &where, int narg, char **arg, int k, Resistance &res);

//! Rolling and twisting resistance of a contact (the pair style's keywords; the wall's follow them).
struct Resistance {
  double roll_k = -1.0, roll_gamma = 0.0, roll_mu = 0.0;    // roll_k < 0: no rolling resistance
  enum { NONE, SDS, MARSHALL } twist = NONE;
  double twist_k = 0.0, twist_gamma = 0.0, twist_mu = 0.0;  // sds
  bool any() const { return roll_k >= 0.0 || twist != NONE; }
  //! Twisting stiffness and limit of a contact: sds's own, or marshall's from the tangential
  //! stiffness kt, contact radius a and friction coefficient mu.
  void twisting(double kt, double a, double mu, double fn, double &k, double &gamma, double &limit) const
  {
    if (twist == MARSHALL) {
      k = 0.5 * kt * a * a;
      gamma = 0.0;
      limit = 2.0 / 3.0 * mu * a * fn;
    } else {
      k = twist_k;
      gamma = twist_gamma;
      limit = twist_mu * fn;
    }
  }
};

/* One step of the rolling and twisting resistance of a contact: relrot = this body's spin minus the
   other's, n from the other body to this one, reff the reduced radius (the sphere's on a wall),
   fn the normal force, kt and a the tangential stiffness and contact radius (marshall), mu the
   friction coefficient; xr (3) and theta the histories. mt: the torque on this body (minus it on
   the other). Returns the elastic energy held. */
inline double resistance_step(const Resistance &res, double *xr, double *theta, const double *relrot, const double *n,
                              double reff, double fn, double kt, double a, double mu, double dt, double *mt)
{
  double held = 0.0;
  for (int m = 0; m < 3; ++m) mt[m] = 0.0;
  if (res.roll_k >= 0.0) {
    double vrl[3] = {reff * (relrot[1] * n[2] - relrot[2] * n[1]), reff * (relrot[2] * n[0] - relrot[0] * n[2]),
                     reff * (relrot[0] * n[1] - relrot[1] * n[0])};
    double fr[3];
    held += rolling_step(xr, n, vrl, res.roll_k, res.roll_gamma, res.roll_mu * fn, dt, fr);
    mt[0] = reff * (n[1] * fr[2] - n[2] * fr[1]);
    mt[1] = reff * (n[2] * fr[0] - n[0] * fr[2]);
    mt[2] = reff * (n[0] * fr[1] - n[1] * fr[0]);
  }
  if (res.twist != Resistance::NONE) {
    double k, gamma, limit, m;
    res.twisting(kt, a, mu, fn, k, gamma, limit);
    double spin = relrot[0] * n[0] + relrot[1] * n[1] + relrot[2] * n[2];
    held += twisting_step(theta, spin, k, gamma, limit, dt, &m);
    for (int c = 0; c < 3; ++c) mt[c] += m * n[c];
  }
  return held;
}

//! The elastic energy the rolling and twisting springs of histories xr, theta hold (no step).
inline double resistance_energy(const Resistance &res, const double *xr, double theta, double kt, double a, double mu)
{
  double held = 0.0;
  if (res.roll_k >= 0.0) held += 0.5 * res.roll_k * (xr[0] * xr[0] + xr[1] * xr[1] + xr[2] * xr[2]);
  if (res.twist != Resistance::NONE) {
    double k, gamma, limit;
    res.twisting(kt, a, mu, 0.0, k, gamma, limit);
    held += 0.5 * k * theta * theta;
  }
  return held;
}

}    // namespace FastrestJGM

#endif
