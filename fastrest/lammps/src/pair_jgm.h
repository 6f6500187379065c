/* pair_style jgm: the Jackson-Green-Marghitu (2010) elastic-plastic normal contact law of fastrest
   between finite-size spheres, with its history, as a LAMMPS plugin. */
#ifndef FASTREST_PAIR_JGM_H
#define FASTREST_PAIR_JGM_H

#include "pair.h"

#include "jgm_contact.h"
#include "jgm_laws.h"

#include <string>
#include <vector>

namespace LAMMPS_NS {

class PairJGM : public Pair {
 public:
  // [0, STATE): the law's row; H_W: energy taken; H_Q: r/(R_i + R_j) and H_C: n x F_t at the last
  // step (the torques' lever and direction, alike seen from i or j); then vectors from j to i
  // (negated for j): H_F the force on i at the last step, H_XI the tangential displacement. With
  // rolling or twisting on, the row goes on: H_M the rolling and twisting torque on i at the last
  // step (negated for j), H_R the rolling displacement and H_T the twist angle (alike seen from i
  // or j). A row holds only what the model steps (NHIST_SLIDE or NHIST_ROLL values: nhist())
  static constexpr int H_W = FastrestJGM::STATE, H_Q = H_W + 1, H_C = H_Q + 1, H_F = H_C + 3, H_XI = H_F + 3,
                       NHIST_SLIDE = H_XI + 3, H_M = NHIST_SLIDE, H_R = H_M + 3, H_T = H_R + 3, NHIST_ROLL = H_T + 1;
  //! single()'s extra values (compute pair/local p1..p7): normal force, |tangential force|, w*,
  //! w_max*, energy dissipated so far, contact radius, elastic energy held
  static constexpr int NSINGLE = 7;

  PairJGM(class LAMMPS *);
  ~PairJGM() override;
  void compute(int, int) override;
  void settings(int, char **) override;
  void coeff(int, char **) override;
  void init_style() override;
  void init_list(int, class NeighList *) override;
  double init_one(int, int) override;
  double single(int, int, int, int, double, double, double, double &) override;

  //! Per local atom: [0] energy dissipated by its contacts (its half of each: those that ended and
  //! the open ones so far), [1] elastic energy its open contacts hold (half), [2] open contacts.
  void per_atom(double **out);

  //! The material of atom type t (set by pair_coeff t t), or nullptr.
  const FastrestJGM::Body *material(int t) const;
  const std::string &unloading() const { return unloading_model; }
  //! Friction, rolling and twisting (the wall's follow them).
  const FastrestJGM::ContactModel &contact_model() const { return model; }
  //! Values of a contact's history row for the model as set: NHIST_ROLL with rolling or twisting on.
  int nhist() const { return model.res.any() ? NHIST_ROLL : NHIST_SLIDE; }

 private:
  std::string unloading_model;
  FastrestJGM::ContactModel model;    // tangential mindlin MU (< 0: none), rolling and twisting
  std::vector<FastrestJGM::Body> mat;    // per type
  std::vector<int> mat_set;
  FastrestJGM::Laws laws;
  std::vector<int> law_of;               // (ntypes + 1)^2: law index of a type pair
  std::string laws_key;                  // what the laws were built for
  std::vector<double> onerad;            // per type: the largest radius at set-up or to be inserted
  int neighprev;                         // single(): where the last partner was found
  class FixJGMHistory *history;

  void allocate();
  void build_laws();
  std::vector<double> model_record() const;
  void check_restored_model();
  void check_restored_rows();
  const double *row_of(int i, int j);
  //! Normal force (force units) and elastic energy held of the contact with row h at w*; ft the
  //! tangential force from the row's last step (its part normal to n removed).
  double contact_state(const double *h, const FastrestJGM::Law &law, double w, double reff, const double *n,
                       double &elastic, double *ft) const;
};

}    // namespace LAMMPS_NS

#endif
