/* The memory this process may still take: the kernel's MemAvailable
 * (/proc/meminfo; without it, free plus buffer memory from sysinfo), lowered
 * to the address-space limit (RLIMIT_AS) if one is set. */
#ifndef CL_MEMINFO_H
#define CL_MEMINFO_H

#include "core/error.h"

/* Bytes available, or CL_EIO if the system does not say. */
cl_status cl_mem_available(double *bytes, cl_error *err);

#endif
