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
  const double *ar = laws.area.data() + 8 * fastrest_law_row(wm, law.first, law.last);
  double a_star = fastrest_law_estrin5((wm - ar[0]) * ar[1], ar[2], ar[3], ar[4], ar[5], ar[6], ar[7]) * s;
  return law.a_c1 * reff * std::sqrt(a_star > 0.0 ? a_star : 0.0);
}

//! Mindlin's stiffness k_t = 8 G* a (pressure x length) on the contact radius of contact_radius.
inline double mindlin_stiffness(const Laws &laws, const Law &law, const double *state, double s, double reff)
{
  return 8.0 * law.g_eff * contact_radius(laws, law, state, s, reff);
}

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

}    // namespace FastrestJGM

#endif
