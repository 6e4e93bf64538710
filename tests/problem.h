/* A problem file loaded into a model, with up to two "section.key=value"
 * assignments (NULL for none), for the tests of the studies (tests run
 * from the repository root).  Header only, included after
 * <criterion/criterion.h>. */
#ifndef CL_TESTS_PROBLEM_H
#define CL_TESTS_PROBLEM_H

#include <criterion/criterion.h>

#include <stdio.h>

#include "io/config.h"
#include "system/model.h"
#include "tmpdir.h"

typedef struct {
    cl_config *cfg;
    cl_model *m;
} pr_problem;

static inline void pr_load(pr_problem *p, const char *path, const char *set1,
                           const char *set2)
{
    cl_error err = {0};
    const char *sets[2] = {set1, set2};
    p->cfg = cl_config_alloc();
    cr_assert_not_null(p->cfg);
    cr_assert_eq(cl_config_load(p->cfg, path, &err), CL_OK, "%s", err.msg);
    for (int k = 0; k < 2; k++)
        if (sets[k])
            cr_assert_eq(cl_config_set(p->cfg, sets[k], &err), CL_OK, "%s",
                         err.msg);
    cr_assert_eq(cl_model_create(p->cfg, &p->m, &err), CL_OK, "%s", err.msg);
}

/* The problem `text` written to p.ini in a fresh temporary directory
 * (its path into dir, 512 bytes, named after tag) and loaded. */
static inline void pr_load_text(pr_problem *p, char *dir, const char *tag,
                                const char *text)
{
    char path[600];
    tmp_mkdtemp(dir, 512, tag);
    snprintf(path, sizeof path, "%s/p.ini", dir);
    tmp_put(path, text);
    pr_load(p, path, NULL, NULL);
}

static inline void pr_free(pr_problem *p)
{
    cl_model_free(p->m);
    cl_config_free(p->cfg);
}

#endif
