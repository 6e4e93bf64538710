/* Choi-Ko parameters shared by several terms. */
#include "forces/choiko.h"

#include <math.h>

cl_status cl_choiko_ks(cl_config *cfg, double *ks, cl_error *err)
{
    return cl_config_double(cfg, "type1", "ks", 200.0, 0.0, INFINITY, ks,
                            err);
}

cl_status cl_choiko_type2_enabled(cl_config *cfg, bool *on, cl_error *err)
{
    return cl_config_bool(cfg, "type2", "enabled", true, on, err);
}

cl_status cl_choiko_type1_enabled(cl_config *cfg, bool *on, cl_error *err)
{
    return cl_config_bool(cfg, "type1", "enabled", true, on, err);
}
