/* Clearing an output directory (outdir.h). */
#include "cli/outdir.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <jansson.h>

#include "io/atomic.h"
#include "io/jsonfile.h"

/* The tables of the other commands, which share out/PROBLEM with run
 * (each study's cl_cli_study.csv, and those of spectrum and eval;
 * tests/test_outdir.c finds them in the sources). */
static const char *const study_outputs[] = {
    "stability.csv", "limits.csv", "convergence.csv", "workprecision.csv",
    "energy.csv", "damping.csv", "damping-modes.csv", "budget.csv",
    "contact.csv", "contact-k.csv", "spectrum.csv", "forces.csv", NULL};

static const char *const run_files[] = {
    "series.csv", "final.csv", "last-good.csv", "stats.csv", "config.ini",
    "run.json", NULL};

static bool in_list(const char *name, size_t len, const char *const *list)
{
    for (size_t k = 0; list[k]; k++)
        if (strlen(list[k]) == len && !strncmp(name, list[k], len))
            return true;
    return false;
}

/* "STEM_NNNNN.vtk" or ".obj" (at least one digit). */
static bool frame_name(const char *name, size_t len, const char *stem)
{
    size_t n = strlen(stem), d = n;
    if (len < n + 6 || strncmp(name, stem, n))
        return false;
    while (d < len && name[d] >= '0' && name[d] <= '9')
        d++;
    return d > n && len - d == 4 &&
           (!strncmp(name + d, ".vtk", 4) || !strncmp(name + d, ".obj", 4));
}

static bool run_name(const char *name, size_t len)
{
    return in_list(name, len, run_files) || frame_name(name, len, "frame_") ||
           frame_name(name, len, "obstacles_");
}

/* Length of NAME in "NAME.tmp.XXXXXX" (cl_afile's temporaries), else 0. */
static size_t temporary_of(const char *name)
{
    const char *at = strstr(name, ".tmp.");
    return at && strlen(at) == 11 ? (size_t)(at - name) : 0;
}

bool cl_cli_run_output(const char *name)
{
    size_t len = temporary_of(name);
    return run_name(name, len ? len : strlen(name));
}

bool cl_cli_clothode_output(const char *name)
{
    size_t len = temporary_of(name);
    len = len ? len : strlen(name);
    return run_name(name, len) || in_list(name, len, study_outputs);
}

/* The names an earlier run.json lists, or NULL if there is none that
 * clothode wrote. */
static json_t *earlier_files(const char *dir)
{
    char path[4200];
    snprintf(path, sizeof path, "%s/run.json", dir);
    const char *why;
    json_error_t je;
    json_t *root = cl_json_read(path, &je, &why);
    json_t *files = json_object_get(root, "files");
    const char *program = json_string_value(json_object_get(root, "program"));
    if (!program || strcmp(program, "clothode") || !json_is_array(files)) {
        json_decref(root);
        return NULL;
    }
    json_incref(files);
    json_decref(root);
    return files;
}

static bool listed(json_t *files, const char *name)
{
    size_t k;
    json_t *f;
    json_array_foreach(files, k, f) {
        const char *n = json_string_value(json_object_get(f, "name"));
        if (n && !strcmp(n, name))
            return true;
    }
    return false;
}

/* Go through dir: refuse it (remove = false) or remove the earlier run's
 * files (remove = true). */
static cl_status sweep(const char *dir, json_t *files, bool remove,
                       cl_error *err)
{
    DIR *d = opendir(dir);
    if (!d)
        return cl_error_set(err, CL_EIO, "cannot read directory '%s': %s",
                            dir, strerror(errno));
    cl_status rc = CL_OK;
    char path[4200];
    struct dirent *e;
    while (!rc && (e = readdir(d))) {
        const char *n = e->d_name;
        if (!strcmp(n, ".") || !strcmp(n, ".."))
            continue;
        snprintf(path, sizeof path, "%s/%s", dir, n);
        bool ours = cl_cli_run_output(n) || (files && listed(files, n));
        if (!remove && ours)
            rc = cl_output_check(path, err);
        else if (!remove && !files && !cl_cli_clothode_output(n))
            rc = cl_error_set(err, CL_EIO, "output directory '%s' is not "
                              "empty and not a clothode output (it holds "
                              "'%s'); choose another --out or empty it",
                              dir, n);
        else if (remove && ours && unlink(path) != 0 && errno != ENOENT)
            rc = cl_error_set(err, CL_EIO, "cannot remove '%s' of the "
                              "earlier run: %s", path, strerror(errno));
    }
    closedir(d);
    return rc;
}

/* This process's output directory, open and locked (flock) until the
 * process ends; -1 for none. */
static int held = -1;

cl_status cl_cli_outdir_hold(const char *dir, cl_error *err)
{
    struct stat st, hs;
    int fd = open(dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) /* the callers report a directory they cannot use */
        return CL_OK;
    if (held >= 0 && fstat(held, &hs) == 0 && fstat(fd, &st) == 0 &&
        hs.st_dev == st.st_dev && hs.st_ino == st.st_ino) {
        close(fd);
        return CL_OK;
    }
    if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
        int e = errno;
        close(fd);
        return e != EWOULDBLOCK ? CL_OK /* a file system without flock */
               : cl_error_set(err, CL_EIO, "output directory '%s' is in "
                              "use by another clothode writing there; wait "
                              "for it to end, or choose another --out", dir);
    }
    if (held >= 0)
        close(held);
    held = fd;
    return CL_OK;
}

/* Check dir (remove false) or clear it (true), held first; a missing dir
 * passes the check and is created by the clearing. */
static cl_status outdir_pass(const char *dir, bool remove, cl_error *err)
{
    struct stat st;
    if (!dir || !*dir)
        return cl_error_set(err, CL_EINVAL, "output directory name is empty");
    if (stat(dir, &st) != 0) {
        cl_status rc = remove ? cl_mkdir_p(dir, err) : CL_OK;
        return rc || !remove ? rc : cl_cli_outdir_hold(dir, err);
    }
    if (!S_ISDIR(st.st_mode))
        return cl_error_set(err, CL_EIO, "cannot use '%s' as the output "
                            "directory: it exists and is not a directory",
                            dir);
    cl_status rc = cl_cli_outdir_hold(dir, err);
    if (rc)
        return rc;
    json_t *files = earlier_files(dir);
    rc = sweep(dir, files, false, err);
    if (!rc && remove)
        rc = sweep(dir, files, true, err);
    json_decref(files);
    return rc;
}

cl_status cl_cli_outdir_check(const char *dir, cl_error *err)
{
    return outdir_pass(dir, false, err);
}

cl_status cl_cli_outdir_prepare(const char *dir, cl_error *err)
{
    return outdir_pass(dir, true, err);
}
