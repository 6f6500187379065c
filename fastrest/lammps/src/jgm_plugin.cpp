/* Registers pair_style jgm, fix wall/jgm, fix jgm/history and compute jgm/atom with LAMMPS (plugin load). */
#include "lammpsplugin_abi.h"

#include "compute_jgm_atom.h"
#include "fix_jgm_history.h"
#include "fix_wall_jgm.h"
#include "pair_jgm.h"

#ifndef FASTREST_LAMMPS_VERSION
#error "FASTREST_LAMMPS_VERSION (the LAMMPS version string) must be defined: build with 'fastrest lammps build'"
#endif
#ifndef FASTREST_VERSION
#define FASTREST_VERSION "unknown"
#endif

using namespace LAMMPS_NS;

static Pair *jgm_pair(LAMMPS *lmp) { return new PairJGM(lmp); }
static Fix *jgm_history(LAMMPS *lmp, int argc, char **argv) { return new FixJGMHistory(lmp, argc, argv); }
static Fix *jgm_wall(LAMMPS *lmp, int argc, char **argv) { return new FixWallJGM(lmp, argc, argv); }
static Compute *jgm_atom(LAMMPS *lmp, int argc, char **argv) { return new ComputeJGMAtom(lmp, argc, argv); }

extern "C" void lammpsplugin_init(void *lmp, void *handle, void *regfunc)
{
  lammpsplugin_regfunc reg = (lammpsplugin_regfunc) regfunc;
  lammpsplugin_t plugin;
  plugin.version = FASTREST_LAMMPS_VERSION;
  plugin.author = "fastrest " FASTREST_VERSION;
  plugin.handle = handle;

  plugin.style = "pair";
  plugin.name = "jgm";
  plugin.info = "Jackson-Green-Marghitu elastic-plastic sphere contact (fastrest " FASTREST_VERSION ")";
  plugin.creator.v1 = (lammpsplugin_factory1 *) &jgm_pair;
  (*reg)(&plugin, lmp);

  plugin.style = "fix";
  plugin.name = "jgm/history";
  plugin.info = "contact histories of pair_style jgm (fastrest " FASTREST_VERSION ")";
  plugin.creator.v2 = (lammpsplugin_factory2 *) &jgm_history;
  (*reg)(&plugin, lmp);

  plugin.style = "fix";
  plugin.name = "wall/jgm";
  plugin.info = "flat walls with the JGM contact law (fastrest " FASTREST_VERSION ")";
  plugin.creator.v2 = (lammpsplugin_factory2 *) &jgm_wall;
  (*reg)(&plugin, lmp);

  plugin.style = "compute";
  plugin.name = "jgm/atom";
  plugin.info = "per-atom energies of pair_style jgm's contacts (fastrest " FASTREST_VERSION ")";
  plugin.creator.v2 = (lammpsplugin_factory2 *) &jgm_atom;
  (*reg)(&plugin, lmp);
}
