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
  // One contact's history: the law's row (fastrest.jit.STATE_SIZE values), the force on atom i and
  // the vector from j to i at the last step, the energy the contact has taken from the atoms.
  static constexpr int H_F = FastrestJGM::STATE, H_DX = H_F + 3, H_W = H_DX + 3, NHIST = H_W + 1;

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

 private:
  std::string unloading_model;
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
