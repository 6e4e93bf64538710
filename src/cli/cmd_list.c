/* clothode list: problems, integrators, force terms, obstacle shapes
 * and linear solvers. */
#include <dirent.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/commands.h"
#include "contact/contact.h"
#include "contact/shape.h"
#include "forces/term.h"
#include "integrators/integrator.h"
#include "io/input.h"
#include "linalg/linsol.h"

/* First comment line of a problem file, among its first 64 lines: its
 * one-line description.  Only a regular file is read (io/input.h). */
static void describe(const char *dir, const char *file)
{
    char path[4096], line[512] = "";
    const char *why;
    snprintf(path, sizeof path, "%s/%s", dir, file);
    FILE *fp = cl_input_open(path, "r", &why);
    if (!fp) {
        printf("  %-20.*s (%s)\n", (int)(strlen(file) - 4), file, why);
        return;
    }
    for (int k = 0; k < 64 && fgets(line, sizeof line, fp) &&
                    line[0] != ';' && line[0] != '#';
         k++)
        line[0] = '\0';
    fclose(fp);
    char *text = line + strspn(line, ";# ");
    text[strcspn(text, "\n")] = '\0';
    printf("  %-20.*s %s\n", (int)(strlen(file) - 4), file, text);
}

static int by_name(const struct dirent **a, const struct dirent **b)
{
    return strcmp((*a)->d_name, (*b)->d_name);
}

static int is_ini(const struct dirent *d)
{
    size_t n = strlen(d->d_name);
    return n > 4 && !strcmp(d->d_name + n - 4, ".ini");
}

static void list_problems(void)
{
    const char *dir = cl_cli_problems_dir();
    struct dirent **names;
    int n = scandir(dir, &names, is_ini, by_name);
    printf("problems (%s/):\n", dir);
    if (n < 0) {
        printf("  (cannot read %s)\n", dir);
        return;
    }
    for (int k = 0; k < n; k++) {
        describe(dir, names[k]->d_name);
        free(names[k]);
    }
    free(names);
}

typedef struct {
    cl_cli_args a;
    const char *kind; /* --integrators KIND, or NULL */
} list_args;

static const cl_cli_opt list_rows[] = {
    {.name = "integrators", .arg = "KIND", .type = CL_CLI_STRING,
     .field = offsetof(list_args, kind),
     .help = "only the names of the integrators of one kind, "
             "comma-separated: explicit (fixed step, a Taylor or symplectic "
             "stability region), implicit (fixed step, a sector region), "
             "fixed (every fixed-step one), adaptive (error control) or "
             "all"},
    CL_CLI_HELP_ROW,
    {.type = CL_CLI_END}};

static const cl_cli_table list_table = {
    .cmd = "list", .synopsis = "", .npos = 0, .rows = list_rows,
    .about = "Names the problems (problems/*.ini or $CLOTHODE_PROBLEMS), the\n"
             "integrators, the force terms, the obstacle shapes and the\n"
             "linear solvers; with --integrators KIND only the integrators\n"
             "of that kind, on one line (for scripts: the registry's\n"
             "methods of a study).\n"};

/* Whether integrator t is of the kind named. */
static bool of_kind(const cl_integrator_type *t, const char *kind)
{
    cl_region_kind r = t->region->kind;
    if (!strcmp(kind, "explicit"))
        return t->fixed_step &&
               (r == CL_REGION_TAYLOR || r == CL_REGION_SYMPLECTIC);
    if (!strcmp(kind, "implicit"))
        return t->fixed_step && r == CL_REGION_SECTOR;
    if (!strcmp(kind, "adaptive"))
        return !t->fixed_step;
    return !strcmp(kind, "all") || t->fixed_step;
}

/* --integrators KIND: the names, comma-separated, on one line. */
static int list_kind(const char *kind)
{
    if (strcmp(kind, "explicit") && strcmp(kind, "implicit") &&
        strcmp(kind, "fixed") && strcmp(kind, "adaptive") &&
        strcmp(kind, "all")) {
        fprintf(stderr, "clothode: list --integrators %s: expected "
                        "explicit, implicit, fixed, adaptive or all\n", kind);
        return 2;
    }
    const char *sep = "";
    for (size_t k = 0; cl_integrator_registry[k]; k++)
        if (of_kind(cl_integrator_registry[k], kind)) {
            printf("%s%s", sep, cl_integrator_registry[k]->name);
            sep = ",";
        }
    putchar('\n');
    return 0;
}

static int list(void *settings)
{
    const list_args *l = settings;
    if (l->kind)
        return list_kind(l->kind);
    list_problems();
    printf("integrators:\n");
    for (size_t k = 0; cl_integrator_registry[k]; k++)
        printf("  %-20s %s\n", cl_integrator_registry[k]->name,
               cl_integrator_registry[k]->doc);
    printf("force terms:\n");
    for (size_t k = 0; cl_term_registry[k]; k++)
        printf("  %-20s %s\n", cl_term_registry[k]->name,
               cl_term_registry[k]->doc);
    printf("  %-20s %s\n", cl_contact_term.name, cl_contact_term.doc);
    printf("obstacle shapes ([obstacle.NAME] shape = ...):\n");
    for (size_t k = 0; cl_shape_registry[k]; k++)
        printf("  %-20s %s\n", cl_shape_registry[k]->name,
               cl_shape_registry[k]->doc);
    printf("linear solvers (--linsol NAME, for the integrators that take "
           "one):\n");
    for (size_t k = 0; cl_linsol_registry[k]; k++)
        printf("  %-20s %s\n", cl_linsol_registry[k]->name,
               cl_linsol_registry[k]->doc);
    return 0;
}

int cl_cmd_list(int argc, char **argv)
{
    list_args l = {0};
    return cl_cli_args_main(argc, argv, &list_table, &l, list);
}
