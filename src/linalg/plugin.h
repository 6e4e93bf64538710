/* Optional parts built as plug-ins: shared objects loaded on first use.
 *
 * The solvers on PETSc (and, through it, MPI) live in clothode-petsc.so,
 * built from the files src/LAYER/NAME_petsc.c (Makefile).  Linking PETSc
 * into every program would cost each run about 50 ms of dynamic linking
 * for its hundred libraries; as a plug-in, only the runs that use it pay,
 * once.  A plug-in calls nothing of the library: what it needs comes in
 * through the arguments of its entry points (docs/architecture.md,
 * "Plug-ins").
 *
 * The plug-in NAME is looked up as clothode-NAME.so in, in order:
 *   $CLOTHODE_PLUGIN_DIR, if set;
 *   the folder of the running program (the build tree);
 *   that folder's ../lib/clothode (an installed tree, `make install`);
 *   PREFIX/lib/clothode, in the installed library (`make install` builds
 *   its copy of this file with CL_PLUGIN_INSTALL_DIR set), so that a
 *   program of one's own linked with it finds the installed plug-in.
 *
 * Interface version.  The types of every entry point live in the headers
 * src/LAYER/NAME_abi.h; the build hashes their preprocessed text (and
 * that of the headers they include) into CL_PLUGIN_ABI, 16 hexadecimal
 * digits in the generated header pluginabi.h (Makefile), so that no change
 * of the interface can leave the version as it was.  Every plug-in
 * defines `const char clp_plugin_abi[] = CL_PLUGIN_ABI;` (for
 * clothode-petsc.so: linalg/pluginabi_petsc.c), and the first plug-in
 * file found is refused, with CL_EUNSUPPORTED naming the file and both
 * versions, unless its version is the program's: a program and a plug-in
 * built from different interfaces never call each other. */
#ifndef CL_PLUGIN_H
#define CL_PLUGIN_H

#include <stddef.h>

#include "core/decls.h"
#include "core/error.h"

CL_BEGIN_DECLS

/* The one message an entry point of a plug-in fills on failure. */
typedef struct {
    char text[512];
} cl_plugin_msg;

/* The address of the entry point `symbol` of plug-in `plugin` ("petsc"),
 * loading the plug-in on the first call.  CL_EUNSUPPORTED, naming every
 * place tried, when it is not found; CL_EINVAL for a missing symbol. */
cl_status cl_plugin_symbol(const char *plugin, const char *symbol,
                           void **address, cl_error *err);

CL_END_DECLS

#endif
