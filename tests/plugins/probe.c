/* A test plug-in (tests/test_plugin.c): one entry point, clp_probe, and
 * the interface version given as PROBE_ABI when it is built (none without
 * it; Makefile, "Test plug-ins"). */
#ifdef PROBE_ABI
extern const char clp_plugin_abi[];
const char clp_plugin_abi[] = PROBE_ABI;
#endif

int clp_probe(void);

int clp_probe(void)
{
    return 42;
}
