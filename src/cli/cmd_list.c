/* clothode list: problems, integrators, force terms and obstacle
 * shapes. */
#include <dirent.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/commands.h"
#include "contact/contact.h"
#include "contact/shape.h"
#include "forces/term.h"
#include "integrators/integrator.h"

/* First comment line of a problem file: its one-line description. */
static void describe(const char *dir, const char *file)
{
    char path[4096], line[512] = "";
    snprintf(path, sizeof path, "%s/%s", dir, file);
    FILE *fp = fopen(path, "r");
    if (fp) {
        while (fgets(line, sizeof line, fp) && line[0] != ';' &&
               line[0] != '#')
            line[0] = '\0';
        fclose(fp);
    }
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

static const cl_cli_opt list_rows[] = {
    CL_CLI_HELP_ROW,
    {.type = CL_CLI_END}};

static const cl_cli_table list_table = {
    .cmd = "list", .synopsis = "", .npos = 0, .rows = list_rows,
    .about = "Names the problems (problems/*.ini or $CLOTHODE_PROBLEMS), the\n"
             "integrators, the force terms and the obstacle shapes.\n"};

static int list(void *settings)
{
    (void)settings;
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
    return 0;
}

int cl_cmd_list(int argc, char **argv)
{
    cl_cli_args a = {0};
    return cl_cli_args_main(argc, argv, &list_table, &a, list);
}
