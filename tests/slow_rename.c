/* Fault injection for test_cli_hostile (issue 54, class 3): preloaded into wetroad, it makes
   every rename() wait 0-40 ms (at random) first, so that two runs committing the same outputs
   overlap and interleave in time as they may on a slow or busy file system. Only the timing
   changes. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <stdlib.h>
#include <time.h>
#include <unistd.h>

int rename(const char* from, const char* to) {
  static int (*real_rename)(const char*, const char*);
  if (!real_rename) real_rename = (int (*)(const char*, const char*))dlsym(RTLD_NEXT, "rename");
  static unsigned seed;
  if (!seed) seed = (unsigned)getpid() ^ (unsigned)time(NULL);
  usleep((useconds_t)(rand_r(&seed) % 40000));
  return real_rename(from, to);
}
