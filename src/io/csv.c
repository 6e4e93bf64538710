/* CSV fields (see csv.h). */
#include "io/csv.h"

#include <string.h>

void cl_csv_quoted(FILE *fp, const char *s)
{
    fputc('"', fp);
    for (; *s; s++) {
        if (*s == '"')
            fputc('"', fp);
        fputc(*s, fp);
    }
    fputc('"', fp);
}

void cl_csv_text(FILE *fp, const char *s)
{
    if (strpbrk(s, ",\"\n"))
        cl_csv_quoted(fp, s);
    else
        fputs(s, fp);
}
