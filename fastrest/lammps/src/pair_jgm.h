/* pair_style jgm: the Jackson-Green-Marghitu (2010) elastic-plastic normal contact law of fastrest
   between finite-size spheres, with its history, as a LAMMPS plugin. */
#ifndef FASTREST_PAIR_JGM_H
#define FASTREST_PAIR_JGM_H

#include "pair.h"

#include "jgm_laws.h"

#include <string>
#include <vector>

namespace LAMMPS_NS {

class PairJGM : public Pair {
 public:
  // [0, STATE): the law's row; H_W: energy taken; H_Q: r/(R_i + R_j) and H_C: n x F_t at the last
  // step (the torques' lever and direction, alike seen from i or j); then vectors from j to i
  // (negated for j): H_F the force on i at the last step, H_XI the tangential displacement
  static constexpr int H_W = FastrestJGM::STATE, H_Q = H_W + 1, H_C = H_Q + 1, H_F = H_C + 3, H_XI = H_F + 3,
                       NHIST = H_XI + 3;

  PairJGM(class LAMMPS *);
  ~PairJGM() override;
  void compute(int, int) override;
  void settings(int, char **) override;
  void coeff(int, char **) override;
  void init_style() override;
  void init_list(int, class NeighList *) override;
  double init_one(int, int) override;

  //! The material of atom type t (set by pair_coeff t t), or nullptr.
  const FastrestJGM::Body *material(int t) const;
  const std::string &unloading() const { return unloading_model; }
  double friction() const { return mu; }

 private:
  std::string unloading_model;
  double mu;    // Coulomb friction coefficient of tangential mindlin; < 0: tangential none
  std::vector<FastrestJGM::Body> mat;    // per type
  std::vector<int> mat_set;
  FastrestJGM::Laws laws;
  std::vector<int> law_of;               // (ntypes + 1)^2: law index of a type pair
  std::string laws_key;                  // what the laws were built for
  double maxrad;
  double ended;    // work of the contacts that ended on this rank (their dissipated energy)
  class FixJGMHistory *history;

  void allocate();
  void build_laws();
};

}    // namespace LAMMPS_NS

#endif
