/* Contact histories of pair_style jgm that survive neighbour-list rebuilds, atoms migrating between
   ranks and restart files.

   Between rebuilds the histories live beside the neighbour list (NVALUES doubles per neighbour).
   Before atoms migrate (pre_exchange) and after a run (post_run, so write_restart sees them) each
   active contact is copied to both of its atoms' partner lists: [partner tag, values...]; these
   travel with the atoms (pack_exchange) and into restart files (pack_restart); values that are
   vectors from one atom to the other are stored negated at the second. After a rebuild
   (post_neighbor) each neighbour pair takes its values from its local atom's partner list. The
   pair style's list is half and newton off, so every contact is on the rank of each of its atoms:
   no ghost communication is needed. */
#ifndef FASTREST_FIX_JGM_HISTORY_H
#define FASTREST_FIX_JGM_HISTORY_H

#include "fix.h"

#include <vector>

namespace LAMMPS_NS {

class FixJGMHistory : public Fix {
 public:
  //! Most contacts one atom may have (a LAMMPS error names the atom past it).
  static constexpr int MAXPARTNER = 64;

  FixJGMHistory(class LAMMPS *, int, char **);
  ~FixJGMHistory() override;
  int setmask() override;
  void setup_post_neighbor() override;
  void pre_exchange() override;
  void min_pre_exchange() override;
  void post_neighbor() override;
  void min_post_neighbor() override;
  void post_run() override;
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

  void set_list(class NeighList *l) { list = l; }
  //! The values of local atom i's neighbours, NVALUES each, in its neighbour-list order.
  double *values(int i) { return vals.data() + offset[i]; }
  int nvalues;
  int flip_lo, flip_hi;    // values flip_lo .. flip_hi - 1 are vectors from atom i to j: negated for j

 private:
  class NeighList *list;
  std::vector<std::vector<double>> partners;
  std::vector<double> vals;
  std::vector<size_t> offset;
  bool current;    // vals hold the histories of the current list

  void to_atoms();
  void add_partner(int i, double tag, const double *v, bool flip);
};

}    // namespace LAMMPS_NS

#endif
