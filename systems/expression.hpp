#pragma once
// The expressions of an aircraft's systems file (docs/systems.md): arithmetic and logic on the
// controls, the systems' own values and the failures, evaluated every systems step.
//
//   cond ? a : b      a || b     a && b     !a     a == b  a != b  a < b  a <= b  a > b  a >= b
//   a + b  a - b  a * b  a / b  -a     ( )     numbers, true (1), false (0)
//   min(a, b)  max(a, b)  clamp(x, lo, hi)  abs(x)  round(x)  floor(x)  mod(a, b)
//   name  or  name.member: a reference, resolved when the model is bound (system_model.hpp)
//
// Every value is a double; a condition is true when it is not 0, and a comparison or a logic
// operator gives 1 or 0. Division or mod by 0 gives 0, so no step makes a NaN. The parse is
// separate from the binding: a syntax error is found when the file is read, an unknown name when
// the names (of the scene's controls) are known. Errors name the column in the expression.

#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace vcockpit::systems {

// A syntax error or an unknown name; the message starts with "at character N: " (1-based).
class ExpressionError : public std::runtime_error {
 public:
  ExpressionError(int column, const std::string& message)
      : std::runtime_error("at character " + std::to_string(column) + ": " + message),
        column_(column) {}
  int column() const { return column_; }

 private:
  int column_;
};

// What a name in an expression reads, once bound.
enum class RefKind : uint8_t {
  kElement,          // a system's value (index: the element)
  kMachineIn,        // 1 while machine `index` is in state `arg`
  kMachineTime,      // seconds machine `index` has been in its state
  kControlIn,        // 1 while control `index` is in position `arg`
  kControlQ,         // control `index`'s coordinate (m, or deg for a revolute joint)
  kControlPosition,  // control `index`'s position (its index among the control's positions)
  kFailure,          // 1 while failure `index` is inserted
  kTime,             // seconds since the systems started
};

struct Ref {
  RefKind kind = RefKind::kElement;
  int index = 0;
  int arg = 0;
};

// A name as written: `name` or `name.member` (member empty), at a 1-based column.
struct Name {
  std::string name;
  std::string member;
  int column = 0;
};

// Resolves a name or throws ExpressionError at its column.
using NameResolver = std::function<Ref(const Name&)>;

// The reader of bound references while evaluating.
class RefReader {
 public:
  virtual ~RefReader() = default;
  virtual double read(const Ref& ref) const = 0;
};

class Expression {
 public:
  Expression() = default;
  // Parses `text`; throws ExpressionError on a syntax error.
  static Expression parse(const std::string& text);
  // A constant (a default where a file gives none).
  static Expression constant(double value);

  const std::string& text() const { return text_; }
  bool empty() const { return code_.empty(); }
  // Every name the expression uses, in order.
  std::vector<Name> names() const;
  // Resolves every name (throws ExpressionError from the resolver).
  void bind(const NameResolver& resolve);
  // The value now (bound first).
  double evaluate(const RefReader& reader) const;

  enum class Op : uint8_t {
    kConst, kLoad, kNot, kNeg, kOr, kAnd, kEq, kNe, kLt, kLe, kGt, kGe, kAdd, kSub, kMul, kDiv,
    kSelect, kMin, kMax, kClamp, kAbs, kRound, kFloor, kMod
  };
  // One instruction of the postfix code (a stack machine).
  struct Instr {
    Op op = Op::kConst;
    double value = 0.0;  // kConst
    int name = -1;       // kLoad: index into names_
  };

 private:
  friend class ExpressionParser;
  std::string text_;
  std::vector<Instr> code_;
  std::vector<Name> names_;
  std::vector<Ref> refs_;  // per name, once bound
  bool bound_ = false;
  int max_depth_ = 0;
};

}  // namespace vcockpit::systems
