// What a type of mobile base brings to a model: its controls (how many, their
// names and units), its pose at home, the controls the solver may change and
// their limits, the constraint rows that tie its body to its controls, its
// collision shape and what statics reports as its effort.
// Omni, differential and legged bases are three implementations of this one
// interface (ccma/bases/); a new base type is one new file there plus one line
// in ccma/bases/base_kinds.cc, where the types are registered.
//
// Every base's first three controls are x [m], y [m] and heading [rad] of its
// body frame on the floor (kBaseX, kBaseY, kBaseHeading below), so formation
// motions, arcs and spacings read them the same way for every type.
#ifndef CCMA_BASE_KIND_H_
#define CCMA_BASE_KIND_H_

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace ceres {
class CostFunction;
}

namespace ccma {

struct MobileBase;
enum class BaseType;

// Offsets of the controls every base type has, within its control block.
constexpr int kBaseX = 0;
constexpr int kBaseY = 1;
constexpr int kBaseHeading = 2;
// The most controls one base may have (the constraint set's scratch size).
constexpr int kMaxBaseControls = 6;

// One control of a base: its name in CSV columns (u<k>_<name>_<unit>) and
// its unit.
struct BaseControl {
  const char* name;
  const char* unit;  // "m" or "rad"
};

// A range [lower, upper] of one control, in its unit, when `limited`.
struct ControlRange {
  bool limited = false;
  double lower = 0, upper = 0;
};

// One component of what a base exerts on the chain, as statics reports it:
// its kind ("base_x", "base_force_z", ...) and value (N or N*m).
struct BaseEffort {
  std::string kind;
  double value = 0;
};

// A base's collision shape: a vertical prism from the floor, turning with
// its heading. A disc of the model's base radius (collision.base_radius or
// the base's `radius`) up to collision.base_height, unless the type says
// otherwise: a rectangle of `half_size` [m] (length along the heading,
// width), reaching up to its body frame's current height.
struct BaseCollisionShape {
  bool rectangle = false;
  Eigen::Vector2d half_size = Eigen::Vector2d::Zero();
};

// One block of constraint rows a base contributes: a cost function of the
// base body's pose and, when `reads_controls`, of its control block.
struct BaseConstraint {
  std::unique_ptr<ceres::CostFunction> cost;
  bool reads_controls = false;
  std::string part;  // "planar", "motor": names the block in messages
};

class BaseKind {
 public:
  virtual ~BaseKind() = default;

  // The model file's spelling of `type:` ("omni", "differential", ...).
  virtual const char* name() const = 0;
  // Its controls in the order of u; the first three are x, y, heading.
  virtual const std::vector<BaseControl>& controls() const = 0;
  int num_controls() const { return static_cast<int>(controls().size()); }
  // Whether the control solver may change control i (0-based in the block).
  virtual bool IsEffective(const MobileBase& /*base*/, int /*i*/) const { return true; }
  // The control block at home (num_controls() values).
  virtual Eigen::VectorXd HomeControls(const MobileBase& base) const;
  // The body frame at home: rotation and origin in the world.
  virtual void HomeFrame(const MobileBase& base, Eigen::Matrix3d* R_WB, Eigen::Vector3d* p_WB) const;
  // Limits of each control (num_controls() entries; none by default).
  virtual std::vector<ControlRange> Limits(const MobileBase& base) const;
  // Its constraint rows, in the constraint set's order: analytic cost
  // functions, or their autodiff twins (tests and benchmarks) when `autodiff`.
  virtual std::vector<BaseConstraint> Constraints(const MobileBase& base, bool autodiff) const = 0;
  // Rows of Constraints() together.
  virtual int num_residuals() const = 0;
  // Its collision shape (default: the disc).
  virtual BaseCollisionShape CollisionShape(const MobileBase& /*base*/) const { return {}; }
  // What the base exerts on the chain, from the generalized efforts of its
  // controls (`effort`, one per control: N for a control in m, N*m for one in
  // rad) at its control block u. By default each control's own effort, kind
  // "base_<control name>".
  virtual std::vector<BaseEffort> Efforts(const double* u, const double* effort) const;
};

// The kind of a base type (ccma/bases/base_kinds.cc).
const BaseKind& KindOf(const MobileBase& base);
// The kind spelled `name` in model files (and its type in *type), or nullptr.
const BaseKind* FindBaseKind(const std::string& name, BaseType* type);
// "omni, differential, ..." for messages.
std::string KnownBaseKinds();

}  // namespace ccma

#endif  // CCMA_BASE_KIND_H_
