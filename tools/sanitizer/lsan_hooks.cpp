// LeakSanitizer settings for the sanitizer build of the programs that draw (irloc-sim and its
// tests): compiled into them only when IRLOC_SANITIZE is on (CMakeLists.txt), never into a
// product build. Fontconfig, under cairo's text, keeps process-lifetime caches that LeakSanitizer
// reports at exit; its frames have no frame pointers, so only the slow unwinder sees
// libfontconfig in every such stack, reliably.

extern "C" const char* __lsan_default_suppressions();
extern "C" const char* __lsan_default_suppressions() { return "leak:libfontconfig.so\n"; }
extern "C" const char* __lsan_default_options();
extern "C" const char* __lsan_default_options() { return "fast_unwind_on_malloc=0"; }
