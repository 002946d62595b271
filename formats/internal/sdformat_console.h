// libsdformat's console without its log file. libsdformat's console, made
// the first time the library logs or is asked for it, opens
// $HOME/.sdformat/sdformat.log (creating the folder) with O_TRUNC and
// without O_NOFOLLOW, and writes element names of the parsed file there: a
// link planted at that name would have ccma overwrite any file the user can
// write (issue 49). libsdformat 12 has no switch for it (only a compile-time
// one), but it opens no file when HOME is unset while the console is made.
#ifndef CCMA_FORMATS_INTERNAL_SDFORMAT_CONSOLE_H_
#define CCMA_FORMATS_INTERNAL_SDFORMAT_CONSOLE_H_

namespace ccma {
namespace internal {

// Makes libsdformat's console once per process, before anything of
// libsdformat runs, with HOME hidden from it (and its "will not log" line
// swallowed), then quiet. Idempotent and thread-safe among its callers;
// HOME is back before it returns. Call before any other libsdformat call:
// once the console exists its log file cannot be closed.
// (HOME is unset for those microseconds: a thread of the host program that
// reads the environment at that moment may miss it, hence the Python module
// calls this when it is imported.)
void QuietSdformatConsole();

}  // namespace internal
}  // namespace ccma

#endif  // CCMA_FORMATS_INTERNAL_SDFORMAT_CONSOLE_H_
