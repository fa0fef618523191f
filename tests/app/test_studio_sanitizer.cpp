// LeakSanitizer suppressions for the test_app binary. Mesa's OSMesa keeps a few allocations from
// OSMesaMakeCurrent (dispatch tables, the glapi context) until the process ends and frees none of
// them at exit: 1.8 kB in 19 blocks whatever the number of contexts created, none of them ours.
// Leaks from our own code are still reported.
#if defined(__SANITIZE_ADDRESS__)
extern "C" const char* __lsan_default_suppressions() {
    return "leak:libOSMesa.so\n";
}
#endif
