/* The plug-in interface version of clothode-petsc.so (linalg/plugin.h):
 * the hash of the NAME_abi.h headers this build made (pluginabi.h),
 * checked by the program that loads it. */
#include "pluginabi.h"

extern const char clp_plugin_abi[];
const char clp_plugin_abi[] = CL_PLUGIN_ABI;
