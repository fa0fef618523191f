// OSMesa keeps a few hundred bytes per context after OSMesaDestroyContext (its framebuffer
// wrapper from OSMesaMakeCurrent). Under BHM_SANITIZE that would fail every GL test at exit;
// the leak is Mesa's, not ours, so LeakSanitizer is told to ignore allocations made inside it.
extern "C" const char* __lsan_default_suppressions() {
    return "leak:libOSMesa.so\n";
}
extern "C" const char* __lsan_default_options() {
    return "print_suppressions=0";
}
