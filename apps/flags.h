// The flags that several `ccma` sub-commands share, declared here once (and
// defined in flags.cc): a command file that uses one of them includes this
// header. Flags that only one command uses are defined in that command's file.
// Every description ends with the unit, so `ccma SUB --help` shows it. A
// shared flag that means something of its own for a command (--from, --out)
// has a generic description here and the command's own in its registry entry
// (commands.h, Command::flag_help).
#ifndef CCMA_APPS_FLAGS_H_
#define CCMA_APPS_FLAGS_H_

#include <gflags/gflags.h>

DECLARE_string(model);       // check simulate control trajectory bench replay
DECLARE_string(obstacles);   // check simulate control trajectory replay workspace view
DECLARE_string(controls);    // simulate control trajectory view
DECLARE_string(waypoints);   // trajectory replay
DECLARE_string(out);         // trajectory plan generate import export bench replay view workspace design
DECLARE_string(from);        // simulate import
DECLARE_string(wrench);      // statics simulate control trajectory view
DECLARE_bool(compensate);    // control trajectory
DECLARE_int32(seed);         // bench replay
DECLARE_string(method);      // control trajectory replay
DECLARE_double(max_step_m);  // control trajectory replay
DECLARE_double(max_step_rad);
DECLARE_double(lambda);
DECLARE_double(max_minutes);  // workspace design

#endif  // CCMA_APPS_FLAGS_H_
