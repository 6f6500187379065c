#include "compute_jgm_atom.h"

#include "pair_jgm.h"

#include "atom.h"
#include "error.h"
#include "force.h"
#include "memory.h"
#include "update.h"

using namespace LAMMPS_NS;

ComputeJGMAtom::ComputeJGMAtom(LAMMPS *lmp, int narg, char **arg) :
    Compute(lmp, narg, arg), nmax(0), values(nullptr), pair(nullptr)
{
  if (narg != 3) error->all(FLERR, "compute jgm/atom: takes no arguments (compute ID group jgm/atom)");
  peratom_flag = 1;
  size_peratom_cols = 3;
}

ComputeJGMAtom::~ComputeJGMAtom() { memory->destroy(values); }

void ComputeJGMAtom::init()
{
  pair = dynamic_cast<PairJGM *>(force->pair_match("jgm", 1));
  if (!pair) error->all(FLERR, "compute jgm/atom needs pair_style jgm");
}

void ComputeJGMAtom::compute_peratom()
{
  invoked_peratom = update->ntimestep;
  if (atom->nmax > nmax) {
    memory->destroy(values);
    nmax = atom->nmax;
    memory->create(values, nmax, 3, "jgm/atom:values");
    array_atom = values;
  }
  pair->per_atom(values);
  int *mask = atom->mask;
  for (int i = 0; i < atom->nlocal; ++i)
    if (!(mask[i] & groupbit)) values[i][0] = values[i][1] = values[i][2] = 0.0;
}

double ComputeJGMAtom::memory_usage() { return 3.0 * nmax * sizeof(double); }
