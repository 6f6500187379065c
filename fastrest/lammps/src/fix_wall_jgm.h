/* fix wall/jgm: flat walls normal to z with fastrest's JGM contact law (sphere on flat, JGM's own
   geometry) and a history per atom and wall. */
#ifndef FASTREST_FIX_WALL_JGM_H
#define FASTREST_FIX_WALL_JGM_H

#include "fix.h"

#include "jgm_contact.h"
#include "jgm_laws.h"

#include <string>
#include <vector>

namespace LAMMPS_NS {

class FixWallJGM : public Fix {
 public:
  FixWallJGM(class LAMMPS *, int, char **);
  ~FixWallJGM() override;
  int setmask() override;
  void init() override;
  void setup(int) override;
  void post_force(int) override;
  void write_restart(FILE *) override;
  void restart(char *) override;
  double compute_vector(int) override;
  void grow_arrays(int) override;
  void copy_arrays(int, int, int) override;
  void set_arrays(int) override;
  int pack_exchange(int, double *) override;
  int unpack_exchange(int, double *) override;
  int pack_restart(int, double *) override;
  void unpack_restart(int, int) override;
  int size_restart(int) override;
  int maxsize_restart() override;
  double memory_usage() override;

 private:
  // per wall (lo, hi): the law's row, the tangential displacement, the rolling displacement and
  // the twist angle
  static constexpr int W_XI = FastrestJGM::STATE, W_R = W_XI + 3, W_T = W_R + 3, PER_WALL = W_T + 1,
                       NV = 2 * PER_WALL;
  double zlo, zhi;
  int has_lo, has_hi;
  FastrestJGM::Body wall;
  std::string unloading;
  double mu_own;    // tangential mindlin MU given here (< 0: tangential none)
  bool mu_given;    // tangential given here; else the pair style's
  FastrestJGM::ContactModel contact;    // the pair style's friction (or mu_own), rolling and twisting
  bool restored;    // histories read from a restart file, checked at the next set-up
  std::vector<double> restored_wall;    // the wall's material in the restart file (empty: none)
  FastrestJGM::Laws laws;
  std::vector<int> law_of;    // per atom type
  std::string laws_key;
  int model_code = 0;    // unloading model index of the laws
  double **hist;
  double wall_force[2], wall_force_all[2];
  int force_flag;
};

}    // namespace LAMMPS_NS

#endif
