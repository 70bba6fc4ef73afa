/*
 * hwy_timer.c: preloaded by `make valgrind` only.
 *
 * OpenImageIO pulls in libhwy (Highway), whose load-time initialiser calls
 * hwy::platform::TimerResolution(), which executes RDTSCP; valgrind 3.19
 * (Debian 12) does not implement RDTSCP and kills every process that loads
 * libhwy with SIGILL before main.  The call goes through libhwy's PLT, so
 * this definition takes its place under LD_PRELOAD.  aabench never uses
 * Highway's timers; the value only has to be a positive tick count.
 */
#include <stdint.h>

/* Highway declares it in a C++ header only: the C declaration is here. */
uint64_t _ZN3hwy8platform15TimerResolutionEv(void);

uint64_t _ZN3hwy8platform15TimerResolutionEv(void)
{
    return 1;
}
