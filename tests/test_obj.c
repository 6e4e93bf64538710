/* Tests for io/obj: the Wavefront OBJ reader, its accepted forms and every
 * refusal with its line number. */
#include <criterion/criterion.h>

#include <stdio.h>
#include <string.h>

#include "cube_obj.h"
#include "io/obj.h"
#include "tmpdir.h"

static char dir[64];
static char path[256];

static void setup(void)
{
    tmp_mkdtemp(dir, sizeof dir, "obj");
    snprintf(path, sizeof path, "%s/m.obj", dir);
}

static void teardown(void)
{
    tmp_rm_rf(dir);
}

TestSuite(obj, .init = setup, .fini = teardown);

static void read_ok(const char *text, cl_obj *m)
{
    tmp_put(path, text);
    cl_error err = {0};
    cr_assert_eq(cl_obj_read(path, m, &err), CL_OK, "%s", err.msg);
}

static void assert_tri(const cl_obj *m, size_t t, int a, int b, int c)
{
    cr_assert(m->tri[t][0] == a && m->tri[t][1] == b && m->tri[t][2] == c,
              "triangle %zu is (%d, %d, %d), expected (%d, %d, %d)", t,
              m->tri[t][0], m->tri[t][1], m->tri[t][2], a, b, c);
}

/* text must be refused with `code` and a message holding both parts. */
static void expect_refused(const char *text, cl_status code,
                           const char *sub1, const char *sub2)
{
    tmp_put(path, text);
    cl_obj m;
    cl_error err = {0};
    cl_status st = cl_obj_read(path, &m, &err);
    cr_assert_eq(st, code, "status %d for \"%s\": %s", st, text, err.msg);
    cr_assert(m.vert == NULL && m.tri == NULL && m.nvert == 0 && m.ntri == 0);
    cr_assert(strstr(err.msg, sub1), "'%s' not in: %s", sub1, err.msg);
    cr_assert(!sub2 || strstr(err.msg, sub2), "'%s' not in: %s", sub2,
              err.msg);
}

Test(obj, cube_of_six_quads)
{
    cl_obj m;
    read_ok(cube_obj, &m);
    cr_assert_eq(m.nvert, 8);
    cr_assert_eq(m.ntri, 12);
    static const double corner[8][3] = {
        {-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
        {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
    for (size_t k = 0; k < 8; k++)
        for (int i = 0; i < 3; i++)
            cr_assert_eq(m.vert[3 * k + i], 0.5 * corner[k][i], "vertex %zu",
                         k);
    assert_tri(&m, 0, 0, 3, 2);     /* f 1 4 3 2 as a fan */
    assert_tri(&m, 1, 0, 2, 1);
    assert_tri(&m, 11, 1, 6, 5);    /* f 2 3 7 6, second triangle */
    cl_obj_free(&m);
    cl_obj_free(&m);                /* harmless twice */
}

Test(obj, relative_indices_and_polygons)
{
    cl_obj m;
    read_ok("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 1.5 0\n"
            "f -5 -4 -3 -2 -1\n"
            "v 0 0 1\n"
            "f 1 -1 2\n", &m);
    cr_assert_eq(m.nvert, 6);
    cr_assert_eq(m.ntri, 4);
    assert_tri(&m, 0, 0, 1, 2);
    assert_tri(&m, 1, 0, 2, 3);
    assert_tri(&m, 2, 0, 3, 4);
    assert_tri(&m, 3, 0, 5, 1);
    cl_obj_free(&m);
}

Test(obj, texture_and_normal_forms_and_ignored_statements)
{
    cl_obj m;
    read_ok("# exported\r\nmtllib m.mtl\r\no thing\r\ng part\r\n"
            "v 0 0 0 1\r\nv\t1e0  0 0\r\nv 0 1 0 # a comment\r\n"
            "v 0 0 +1.0\r\n"
            "vt 0 0\r\nvt 1 0\r\nvt 0 1\r\nvn 0 0 1\r\n"
            "usemtl red\r\ns off\r\n\r\n   \r\n"
            "f 1/1 2/2 3/3\r\n"
            "f 1//1 3//1 4//1\r\n"
            "f 1/1/1 4/3/1 2/2/1\r\n"
            "f -4/-3/-1 -2//-1 -1/1\r\n"
            "f 2 3 4", &m);   /* no final newline */
    cr_assert_eq(m.nvert, 4);
    cr_assert_eq(m.ntri, 5);
    cr_assert_eq(m.vert[3], 1.0);
    cr_assert_eq(m.vert[11], 1.0);
    assert_tri(&m, 0, 0, 1, 2);
    assert_tri(&m, 1, 0, 2, 3);
    assert_tri(&m, 2, 0, 3, 1);
    assert_tri(&m, 3, 0, 2, 3);
    assert_tri(&m, 4, 1, 2, 3);
    cl_obj_free(&m);
}

#define TRI "v 0 0 0\nv 1 0 0\nv 0 1 0\n"

Test(obj, malformed_files_name_the_line)
{
    static const struct {
        const char *text, *sub1, *sub2;
    } bad[] = {
        {"", "m.obj:1:", "empty file"},
        {"# nothing\n\n", "m.obj:2:", "without vertices"},
        {TRI "# no faces\n", "m.obj:4:", "without faces"},
        {TRI "f 0 1 2\n", "m.obj:4:", "vertex index 0"},
        {TRI "f 1 2 4\n", "m.obj:4:", "index 4 out of range (3 vertices"},
        {TRI "f 1 2 -4\n", "m.obj:4:", "index -4 out of range"},
        {"f 1 2 3\n" TRI, "m.obj:1:", "index 1 out of range (0 vertices"},
        {TRI "f 1 2 99999999999999999999\n", "m.obj:4:",
         "index 99999999999999999999 out of range"},
        {"v 0 nan 0\n", "m.obj:1:", "\"nan\" is not a finite number"},
        {"v 0 0 0\nv inf 0 0\n", "m.obj:2:", "\"inf\" is not a finite"},
        {"v 0 0 1e999\n", "m.obj:1:", "not a finite number"},
        {TRI "f 1 2 1\n", "m.obj:4:", "vertices 1, 2, 1 repeats a vertex"},
        {TRI "v 2 0 0\nf 1 2 4\n", "m.obj:5:",
         "vertices 1, 2, 4 has zero area"},
        {TRI "v 0 0 0\nf 1 2 4\n", "m.obj:5:", "zero area"},
        {TRI "f 1 2 3 3\n", "m.obj:4:", "vertices 1, 3, 3 repeats"},
        {"v 0 0 zero\n", "m.obj:1:", "\"zero\" is not a number"},
        {"v 0 0 1.5x\n", "m.obj:1:", "\"1.5x\" is not a number"},
        {"v 0 0\n", "m.obj:1:", "3 or 4 numbers (x y z [w]), found 2"},
        {"v 0 0 0 1 2\n", "m.obj:1:", "found more"},
        {TRI "f 1 2\n", "m.obj:4:", "at least 3 vertices, found 2"},
        {TRI "f 1 2 x\n", "m.obj:4:", "\"x\" is not a face vertex"},
        {TRI "f 1 2 3/\n", "m.obj:4:", "\"3/\" is not a face vertex"},
        {TRI "f 1 2 3/1/2/3\n", "m.obj:4:", "not a face vertex"},
        {TRI "f 1 2 3//\n", "m.obj:4:", "not a face vertex"},
        {TRI "f 1 2 3.0\n", "m.obj:4:", "not a face vertex"},
        {TRI "l 1 2\n", "m.obj:4:", "unsupported statement \"l\""},
        {"v 0 0 0\n\nv 1 0 0 \\\n 1\n", "m.obj:3:", "\"\\\" is not"},
    };
    for (size_t k = 0; k < sizeof bad / sizeof *bad; k++)
        expect_refused(bad[k].text, CL_EPARSE, bad[k].sub1, bad[k].sub2);
}

Test(obj, nul_byte_is_refused)
{
    static const char text[] = TRI "f 1 2\0 3\n";
    FILE *fp = fopen(path, "wb");
    cr_assert_not_null(fp);
    cr_assert_eq(fwrite(text, 1, sizeof text - 1, fp), sizeof text - 1);
    cr_assert_eq(fclose(fp), 0);
    cl_obj m;
    cl_error err = {0};
    cr_assert_eq(cl_obj_read(path, &m, &err), CL_EPARSE);
    cr_assert(strstr(err.msg, "m.obj:4: NUL byte"), "%s", err.msg);
}

/* A 10 MB line is refused at its line after CL_OBJ_MAX_LINE characters;
 * a line of exactly CL_OBJ_MAX_LINE characters is read. */
Test(obj, long_lines)
{
    FILE *fp = fopen(path, "w");
    cr_assert_not_null(fp);
    fputs(TRI "v 1 1 1", fp);
    for (int k = 0; k < CL_OBJ_MAX_LINE - 7; k++)
        fputc(' ', fp);
    fputs("\nf 1 2 3\nv 0 0 1", fp);
    for (long k = 0; k < 10L * 1024 * 1024; k++)
        fputc(k % 2 ? ' ' : '1', fp);
    fputs("\nf 1 2 3\n", fp);
    cr_assert_eq(fclose(fp), 0);
    cl_obj m;
    cl_error err = {0};
    cr_assert_eq(cl_obj_read(path, &m, &err), CL_EPARSE);
    cr_assert(strstr(err.msg, "m.obj:6: line longer than 65536 characters"),
              "%s", err.msg);
    cr_assert_null(m.vert);
}

Test(obj, missing_file_and_directory)
{
    cl_obj m;
    cl_error err = {0};
    cr_assert_eq(cl_obj_read(path, &m, &err), CL_EIO);
    cr_assert(strstr(err.msg, path) && strstr(err.msg, "No such file"), "%s",
              err.msg);
    cr_assert_eq(cl_obj_read(dir, &m, &err), CL_EIO);
    cr_assert(strstr(err.msg, dir), "%s", err.msg);
}
