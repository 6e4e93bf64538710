/* JSON documents from regular files (see jsonfile.h). */
#include "io/jsonfile.h"

#include <stdio.h>

#include "io/input.h"

json_t *cl_json_read(const char *path, json_error_t *je, const char **why)
{
    FILE *fp = cl_input_open(path, "r", why);
    if (!fp)
        return NULL;
    *why = NULL;
    json_t *root = json_loadf(fp, 0, je);
    (void)fclose(fp);
    return root;
}
