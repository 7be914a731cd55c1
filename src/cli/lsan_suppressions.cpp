// Leaks that are not relief's, for the AddressSanitizer build's LeakSanitizer
// (read through this hook; ignored in other builds): fontconfig keeps its
// configuration and font patterns for the process's life (freed only by
// FcFini, which Pango's cached font map forbids); the overlays' text goes
// through it (annotate/paint.cpp).
extern "C" const char* __lsan_default_suppressions() { return "leak:libfontconfig.so\n"; }
