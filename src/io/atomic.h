/* Atomic output files and output directories.
 *
 * Every output file is first written to a temporary file "PATH.tmp.XXXXXX"
 * in the same directory and only renamed onto PATH once it is complete and
 * synced to disk, so a reader never sees a half-written PATH and a crash
 * leaves the previous PATH (if any) intact.
 *
 *   cl_afile af;
 *   if (cl_afile_open(&af, path, err)) return err->code;
 *   if (fprintf(af.fp, ...) < 0) return cl_afile_fail(&af, err);
 *   return cl_afile_commit(&af, err);
 *
 * After commit (successful or not) or abort the cl_afile is reset, so a
 * second abort is a harmless no-op. */
#ifndef CL_ATOMIC_H
#define CL_ATOMIC_H

#include <stdio.h>

#include "core/decls.h"
#include "core/error.h"

CL_BEGIN_DECLS

typedef struct {
    FILE *fp;       /* write here; NULL when nothing is open */
    char *path;     /* final name */
    char *tmp;      /* temporary name */
} cl_afile;

/* Whether path may receive an output: CL_OK if it does not exist or is a
 * regular file; CL_EIO naming what it is when it is anything else (a
 * device such as /dev/full, a FIFO, a directory, a symbolic link), which
 * the rename of an atomic write would replace; CL_EINVAL for "". */
cl_status cl_output_check(const char *path, cl_error *err);

/* Create the temporary file (mode 0666 minus umask) and open af->fp on it.
 * CL_EIO with the path and the system's reason if it cannot be created,
 * and, before anything is created, if path is not a regular file
 * (cl_output_check; checked again before the rename). */
cl_status cl_afile_open(cl_afile *af, const char *path, cl_error *err);

/* Check for earlier write errors, then fflush, fsync, fclose and rename the
 * temporary file onto the final path.  On any failure the temporary file is
 * removed and CL_EIO names the path and the reason. */
cl_status cl_afile_commit(cl_afile *af, cl_error *err);

/* Close and remove the temporary file; the final path is not touched. */
void cl_afile_abort(cl_afile *af);

/* A write to af->fp failed: CL_EIO "cannot write 'PATH': reason" with
 * errno's reason (EIO's when errno is 0), read before anything else runs.
 * The file stays open. */
cl_status cl_afile_write_error(const cl_afile *af, cl_error *err);

/* The same, then cl_afile_abort. */
cl_status cl_afile_fail(cl_afile *af, cl_error *err);

/* Create directory `dir` and any missing parents (mode 0777 minus umask).
 * An existing directory is fine; CL_EIO if a component exists as something
 * other than a directory or cannot be created; CL_EINVAL for "". */
cl_status cl_mkdir_p(const char *dir, cl_error *err);

CL_END_DECLS

#endif
