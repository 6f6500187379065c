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

// one style of the plugin: creator v1 (a pair style) or v2 (fixes and computes take arguments)
static void add(lammpsplugin_regfunc reg, void *lmp, lammpsplugin_t &plugin, const char *style, const char *name,
                const char *info, lammpsplugin_factory1 *v1, lammpsplugin_factory2 *v2)
{
  plugin.style = style;
  plugin.name = name;
  plugin.info = info;
  if (v1) plugin.creator.v1 = v1;
  else plugin.creator.v2 = v2;
  (*reg)(&plugin, lmp);
}

extern "C" void lammpsplugin_init(void *lmp, void *handle, void *regfunc)
{
  auto reg = (lammpsplugin_regfunc) regfunc;
  lammpsplugin_t plugin;
  plugin.version = FASTREST_LAMMPS_VERSION;
  plugin.author = "fastrest " FASTREST_VERSION;
  plugin.handle = handle;
  add(reg, lmp, plugin, "pair", "jgm",
      "Jackson-Green-Marghitu elastic-plastic sphere contact (fastrest " FASTREST_VERSION ")",
      (lammpsplugin_factory1 *) &jgm_pair, nullptr);
  add(reg, lmp, plugin, "fix", "jgm/history", "contact histories of pair_style jgm (fastrest " FASTREST_VERSION ")",
      nullptr, (lammpsplugin_factory2 *) &jgm_history);
  add(reg, lmp, plugin, "fix", "wall/jgm", "flat walls with the JGM contact law (fastrest " FASTREST_VERSION ")",
      nullptr, (lammpsplugin_factory2 *) &jgm_wall);
  add(reg, lmp, plugin, "compute", "jgm/atom",
      "per-atom energies of pair_style jgm's contacts (fastrest " FASTREST_VERSION ")", nullptr,
      (lammpsplugin_factory2 *) &jgm_atom);
}
