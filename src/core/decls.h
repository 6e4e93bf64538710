/* What lets a C++ program include clothode's headers (README
 * "Installing"), as GSL's __BEGIN_DECLS does for its own: every header
 * puts its declarations between CL_BEGIN_DECLS and CL_END_DECLS, which
 * give them C linkage under a C++ compiler and are empty in C, and
 * writes a restrict-qualified parameter as CL_RESTRICT, C's restrict and
 * GNU C++'s __restrict (C++ has no restrict). */
#ifndef CL_DECLS_H
#define CL_DECLS_H

#ifdef __cplusplus
#define CL_BEGIN_DECLS extern "C" {
#define CL_END_DECLS }
#define CL_RESTRICT __restrict
#else
#define CL_BEGIN_DECLS
#define CL_END_DECLS
#define CL_RESTRICT restrict
#endif

#endif
