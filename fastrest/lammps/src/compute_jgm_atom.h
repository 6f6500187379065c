/* compute ID group jgm/atom: per-atom energies of pair_style jgm's contacts, for maps of where the
   energy goes. Columns: [1] energy dissipated by the atom's contacts so far (half of each contact's,
   those that ended and the open ones), [2] elastic energy its open contacts hold (half), [3] its
   open contacts. Summed over atoms, [1] and [2] are compute pair jgm's [1] and [2]. */
#ifndef FASTREST_COMPUTE_JGM_ATOM_H
#define FASTREST_COMPUTE_JGM_ATOM_H

#include "compute.h"

namespace LAMMPS_NS {

class ComputeJGMAtom : public Compute {
 public:
  ComputeJGMAtom(class LAMMPS *, int, char **);
  ~ComputeJGMAtom() override;
  void init() override;
  void compute_peratom() override;
  double memory_usage() override;

 private:
  int nmax;
  double **values;
  class PairJGM *pair;
};

}    // namespace LAMMPS_NS

#endif
