// The documented input ranges of ccma (docs/model_format.md, docs/cli.md).
//
// Input is hostile until validated: every number, count, size and duration
// that reaches a solver, a loop bound or an integer conversion is checked
// against one of these first, with a message that names where it came from.
// They are generous for any real mechanism (a 10 km workspace, 100k bodies)
// and small enough that no loop runs away and no conversion overflows.
#ifndef CCMA_LIMITS_H_
#define CCMA_LIMITS_H_

#include <cstddef>

namespace ccma {

// Every number in a model file, and every control or target value, lies in
// [-kMaxMagnitude, kMaxMagnitude] (metres or radians).
constexpr double kMaxMagnitude = 1e4;

// Names (model, bodies, bases, joints): 1 to kMaxNameLength characters from
// [A-Za-z0-9_-].
constexpr std::size_t kMaxNameLength = 64;
// A model's free-text description, in bytes.
constexpr std::size_t kMaxDescriptionLength = 4096;

// Model files are read up to this many bytes (4 MiB: a 1000-agent model is
// 0.7 MB; yaml-cpp builds its whole tree before any check, ~250 bytes of
// memory per byte of a dense file), and must be regular files.
constexpr std::size_t kMaxModelFileBytes = std::size_t{4} << 20;
// Bodies (including mobile bases) and joints per model.
constexpr int kMaxBodies = 100000;
constexpr int kMaxJoints = 200000;
// Wheels per mobile base.
constexpr int kMaxWheels = 64;
// Visual meshes (`meshes:` of bodies and bases): per body, per model, and the
// length of one mesh's file path in bytes.
constexpr int kMaxMeshesPerBody = 64;
constexpr int kMaxMeshes = 10000;
constexpr std::size_t kMaxMeshPathLength = 4096;
// Collision geometry: capsules (`collision.links`), ignored pairs and
// obstacles (model file and --obstacles files together) per model.
constexpr int kMaxCollisionLinks = 10000;
constexpr int kMaxIgnoredPairs = 10000;
constexpr int kMaxObstacles = 10000;
// --obstacles files are read up to this many bytes.
constexpr std::size_t kMaxObstacleFileBytes = std::size_t{4} << 20;

// Waypoint files: at most this many bytes (16 MiB; a million rows of a path
// fit in 14 MB) and this many waypoints.
constexpr std::size_t kMaxWaypointFileBytes = std::size_t{16} << 20;
constexpr int kMaxWaypoints = 1000000;
// Waypoint times lie in [-kMaxTime, kMaxTime] seconds.
constexpr double kMaxTime = 1e6;

// Path steps of one control move or trajectory, and sub-steps of one assembly.
constexpr long kMaxPathSteps = 100000;
constexpr long kMaxAssemblySubsteps = 100000;

// Replay: controller ticks (duration x controller rate) and output samples.
constexpr long kMaxReplayTicks = 10000000;
constexpr long kMaxReplaySamples = 1000000;

// Statics: constraint rows x state coordinates of the dense equilibrium
// solve (64 MB), problems/internal/equilibrium.h.
constexpr long kMaxStaticsEntries = 8000000;

}  // namespace ccma

#endif  // CCMA_LIMITS_H_
