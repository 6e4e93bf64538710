/* Input files: only regular files are read.  A FIFO would block the open
 * until some process writes to it (and a signal does not end a blocked
 * open), a device may never end; both are refused, with what they are. */
#ifndef CL_INPUT_H
#define CL_INPUT_H

#include <stdbool.h>
#include <stdio.h>
#include <sys/types.h>

#include "core/decls.h"
#include "core/error.h"

CL_BEGIN_DECLS

/* fopen(path, mode) for reading, of a regular file only (a symbolic link
 * to one is followed): opened without blocking, then checked.  NULL when
 * it cannot be opened or is not a regular file, *why saying which
 * (strerror's text, or "it is a FIFO, not a regular file", ...). */
FILE *cl_input_open(const char *path, const char *mode, const char **why);

/* getline(3) with a bound: the next line of fp (its newline kept) into
 * *line (grown to max + 1 bytes at most, getline's contract otherwise);
 * its length, which may count NUL bytes; CL_INPUT_END at the end of the
 * file or on a read error (ferror); CL_INPUT_LONG when the line is longer
 * than max bytes, the rest of it unread, so that a file of one huge line
 * is refused before it fills the memory; CL_INPUT_NOMEM when the buffer
 * could not grow. */
enum { CL_INPUT_END = -1, CL_INPUT_LONG = -2, CL_INPUT_NOMEM = -3 };
ssize_t cl_input_line(FILE *fp, char **line, size_t *cap, size_t max);

/* Whether a line cl_input_line returned (len, not CL_INPUT_END) is one a
 * reader of text can parse: CL_OK; else, with "path:lineno: ...",
 * CL_ENOMEM for no memory, CL_EPARSE for a line longer than max bytes
 * (`hint` after the message: "" or " (why lines are short)") or for a
 * NUL byte (`kind` names the file: "a state file"). */
cl_status cl_input_line_ok(const char *line, ssize_t len, size_t max,
                           const char *path, size_t lineno, const char *kind,
                           const char *hint, cl_error *err);

/* Whether paths a and b name the same existing file (or directory), by
 * device and inode: through links and other spellings. */
bool cl_same_file(const char *a, const char *b);

/* Whether `recorded`, a path written down elsewhere (a sweep's problem
 * file, perhaps on the machine that planned it), names the input file
 * `mine`: the same file; else, when `recorded` can be read here, the same
 * bytes; else (a sweep copied from another machine) the same file name. */
bool cl_same_input(const char *recorded, const char *mine);

/* What a file of mode `mode` (from stat) is, for messages: "a regular
 * file", "a directory", "a symbolic link", "a FIFO", "a device", "a
 * socket". */
const char *cl_file_kind(mode_t mode);

CL_END_DECLS

#endif
