/* The contact laws of a set of material pairs, built by fastrest (Python) and read here.

   Rank 0 runs `FASTREST_PYTHON -m fastrest lammps law`, which writes one binary file of every
   law's rows (fastrest.jit's ForwardData.law_rows) and critical values; every rank then parses
   the same bytes. The rows are fastrest's own, so the plugin holds no copy of the model. */
#ifndef FASTREST_JGM_LAWS_H
#define FASTREST_JGM_LAWS_H

#include "fastrest_law.h"
#include "jgm_law_file.h"
#include "lammps.h"

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace FastrestJGM {

//! Number of doubles of one contact's normal history row (fastrest.jit.STATE_SIZE).
constexpr int STATE = FASTREST_STATE_SIZE;

struct Body {
  double E, nu, Sy, Et;    // the simulation's pressure units; Et = 0: no hardening
};

struct LawRequest {
  bool flat;           // false: two spheres; true: sphere (a) on a flat body (b)
  Body a, b;
  std::string label;   // names the pair in fastrest's error messages
};

struct Law {
  double omega_c1;     // critical interference over the reduced radius (-)
  double p_c1;         // critical force over the reduced radius squared (pressure units)
  double w_end;        // the law's end, w* = omega/omega_c (-)
  int64_t first, last; // this law's rows: first .. first + last
  double a_c1;         // critical contact radius over the reduced radius (-)
  double g_eff;        // Mindlin's combined shear modulus G* (pressure units)
};

struct Laws {
  std::vector<double> rows;   // all laws' rows, LawFile::ROW doubles each
  std::vector<double> area;   // A* on the same cells: [center, 1/half_width, c0..c5] (LawFile::AREA_ROW) each
  std::vector<Law> law;
};

//! A number of the input script, finite; else a LAMMPS error "WHERE: WHAT = TEXT is not finite".
double finite_number(LAMMPS_NS::LAMMPS *lmp, const std::string &where, const char *what, const char *text);

//! A body's material from the script's texts of E, nu, Sy and Et (nullptr: Et = 0), checked by
//! fastrest.Material's rules: E > 0, 0 <= nu < 0.5, Sy > 0, 0 <= Et < E, else a LAMMPS error naming
//! the value (all finite: LAMMPS reads no infinity). What fastrest refuses of a pair (Sy >= E',
//! JGM eq 1) is its message, from the law's build.
Body read_body(LAMMPS_NS::LAMMPS *lmp, const std::string &where, const char *E, const char *nu, const char *Sy,
               const char *Et);

//! Offset of the nth fix's record among one atom's `width` restart values (each record led by its
//! length), or -1 where a length before it is not a whole number >= 1 within them.
inline int restart_record(const double *extra, int width, int nth)
{
  double m = 0.0;
  for (int k = 0; k < nth; ++k) {
    double size = m < width ? extra[static_cast<int>(m)] : -1.0;
    if (!(size >= 1.0 && m + size <= width) || size != std::floor(size)) return -1;
    m += size;
  }
  return m < width ? static_cast<int>(m) : -1;
}

//! Whether a history row of n values is in use (a closed or virgin contact's is all zeros).
inline bool row_open(const double *row, int n)
{
  for (int k = 0; k < n; ++k)
    if (row[k] != 0.0) return true;
  return false;
}

//! Whether a contact at w* with history row `state` has ended: the overlap and the force both gone
//! (w* <= 0 and w* <= w_res*; w_res* < 0 just above w* = 1.9 for nu < 0.32, where the unloading
//! branch still pushes at zero overlap).
inline bool contact_over(double w, const double *state) { return w <= 0.0 && w <= state[2]; }

//! Where w* lies on the elastic branch through the maximum: s = (w* - w_res*)/delta in [0, 1]
//! (1 while loading, 0 at or below w_res* and for a virgin row).
inline double elastic_fraction(const double *state, double w)
{
  double s = state[3] > 0.0 ? (w - state[2]) / state[3] : 0.0;
  return s > 1.0 ? 1.0 : (s > 0.0 ? s : 0.0);
}

//! Pascals per pressure unit of a LAMMPS units style (si 1, cgs 0.1, micro 1e3, nano 1e6), or 0
//! for the styles with no meaning for the law (lj, real, metal, electron).
double pascal_per_unit(const char *units);

//! Index of an unloading model (jcg 0, etsion 1, brake 2; -1 for another name).
int unloading_index(const std::string &model);

//! Elastic energy held by the normal law at elastic fraction s, over the simulation's pressure
//! unit conversion: the integral of the unloading branch, JGM eq (32), (2/5) P_max delta s^(5/2).
inline double normal_energy(const double *state, double s, const Law &law, double reff)
{
  return 0.4 * state[1] * state[3] * s * s * std::sqrt(s) * law.p_c1 * law.omega_c1 * reff * reff * reff;
}

//! Build the laws of `requests` (collective: every rank calls it), moduli and strengths in units of
//! `pascal` Pa; a LAMMPS error on failure.
void request_laws(LAMMPS_NS::LAMMPS *lmp, const std::vector<LawRequest> &requests,
                  const std::string &unloading, double pascal, Laws &out);

//! "" if the normal history row `state` is one law `k` of `laws` can have written (w_max* in
//! (0, the law's end], P*(w_max), w_res* and delta those of the law at w_max), else what is wrong.
std::string row_problem(const Laws &laws, int k, const double *state);

//! Parse the bytes of a law file; returns "" or what is wrong with them.
std::string parse_laws(const std::vector<char> &bytes, size_t expected, Laws &out);

}    // namespace FastrestJGM

#endif
