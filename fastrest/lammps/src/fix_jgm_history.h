/* Contact histories of pair_style jgm that survive neighbour-list rebuilds, atoms migrating between
   ranks and restart files.

   Between rebuilds the histories live beside the neighbour list (NVALUES doubles per neighbour).
   Before atoms migrate (pre_exchange) and after a run (post_run, so write_restart sees them) each
   active contact is copied to both of its atoms' partner lists: [partner tag, values...]; these
   travel with the atoms (pack_exchange) and into restart files (pack_restart); values that are
   vectors from one atom to the other are stored negated at the second. After a rebuild
   (post_neighbor) each neighbour pair takes its values from its local atom's partner list. The
   pair style's list is half and newton off, so every contact is on the rank of each of its atoms:
   no ghost communication is needed. The partner lists grow as needed (no limit on contacts per
   atom). Each atom also carries its share of the energy dissipated by its contacts that ended.

   The fix's global restart record holds the values per contact and the pair style's model (its
   materials and options), so that a run read back from a restart file can refuse another model
   for contacts that are open. */
#ifndef FASTREST_FIX_JGM_HISTORY_H
#define FASTREST_FIX_JGM_HISTORY_H

#include "fix.h"

#include <vector>

namespace LAMMPS_NS {

class FixJGMHistory : public Fix {
 public:
  FixJGMHistory(class LAMMPS *, int, char **);
  ~FixJGMHistory() override;
  int setmask() override;
  void setup_post_neighbor() override;
  void pre_exchange() override;
  void min_pre_exchange() override;
  void post_neighbor() override;
  void min_post_neighbor() override;
  void post_run() override;
  void write_restart(FILE *) override;
  void restart(char *) override;
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
  double *values(int i) { return vals.data() + offset[i] * nvalues; }
  //! Per neighbour of local atom i: 1 where its row is in use (the pair style keeps these as it
  //! opens and ends contacts), so that pairs apart are told without reading their rows.
  unsigned char *in_use(int i) { return used.data() + offset[i]; }
  //! Open contacts local atom i carries (between a migration and the next rebuild).
  int partner_count(int i) const { return static_cast<int>(partners[i].size() / (1 + nvalues)); }
  //! Energy dissipated by local atom i's contacts that ended (its half of each).
  double &ended(int i) { return ended_energy[i]; }
  //! Another row layout (values per contact, negated range) for the next run: each open contact
  //! keeps its first values, the rest start at 0 (the layouts share a prefix; PairJGM::nhist).
  void relayout(int nvalues, int flip_lo, int flip_hi);

  //! The model the pair style runs (written to restart files) and the one a restart file held
  //! (empty: none read); see PairJGM::model_record.
  std::vector<double> model, restored_model;
  //! Set when histories were read from a restart file; the pair style checks them and clears it.
  bool restored_rows;

  int nvalues;
  int flip_lo, flip_hi;    // values flip_lo .. flip_hi - 1 are vectors from atom i to j: negated for j
  int restored_nvalues;    // values per contact of the restart file read (its global record)

 private:
  class NeighList *list;
  std::vector<std::vector<double>> partners;
  std::vector<double> ended_energy;
  std::vector<double> vals;
  std::vector<unsigned char> used;
  std::vector<size_t> offset;    // per local atom: its first neighbour's index in used (rows: x nvalues)
  bool current;    // vals hold the histories of the current list

  void to_atoms();
  void add_partner(int i, double tag, const double *v, bool flip);
  void check_box();
  static void check_layout(class Error *, int nvalues, int flip_lo, int flip_hi);
};

}    // namespace LAMMPS_NS

#endif
