#include "systems/expression.hpp"

#include <array>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>

namespace vcockpit::systems {

// Recursive descent, lowest precedence first: select, or, and, comparison, sum, product,
// unary, primary. Emits postfix code as it goes.
class ExpressionParser {
 public:
  explicit ExpressionParser(Expression& out) : out_(out), s_(out.text_) {}

  void parse() {
    skip_space();
    if (pos_ >= s_.size()) fail("empty expression");
    select();
    skip_space();
    if (pos_ < s_.size()) fail("unexpected '" + std::string(1, s_[pos_]) + "'");
    // the stack depth the code needs, checked once here
    int depth = 0, max_depth = 0;
    for (const Expression::Instr& i : out_.code_) {
      depth += stack_effect(i.op);
      max_depth = std::max(max_depth, depth);
    }
    if (max_depth > kMaxDepth) fail("nested too deeply");
    out_.max_depth_ = max_depth;
  }

  static constexpr int kMaxDepth = 32;

 private:
  using Op = Expression::Op;

  static int stack_effect(Op op) {
    switch (op) {
      case Op::kConst: case Op::kLoad: return 1;
      case Op::kNot: case Op::kNeg: case Op::kAbs: case Op::kRound: case Op::kFloor: return 0;
      case Op::kSelect: case Op::kClamp: return -2;
      default: return -1;
    }
  }

  [[noreturn]] void fail(const std::string& message) const {
    throw ExpressionError(static_cast<int>(pos_) + 1, message);
  }
  void skip_space() {
    while (pos_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[pos_]))) ++pos_;
  }
  bool accept(const char* token) {
    skip_space();
    const std::size_t n = std::char_traits<char>::length(token);
    if (s_.compare(pos_, n, token) != 0) return false;
    // "<" must not take the first half of "<=", "!" of "!=", "=" alone is no operator
    if (n == 1 && pos_ + 1 < s_.size() && s_[pos_ + 1] == '=' &&
        (token[0] == '<' || token[0] == '>' || token[0] == '!' || token[0] == '='))
      return false;
    pos_ += n;
    return true;
  }
  void expect(const char* token) {
    if (!accept(token)) fail(std::string("expected '") + token + "'");
  }
  void emit(Op op, double value = 0.0, int name = -1) { out_.code_.push_back({op, value, name}); }

  // Nesting (parentheses, unary operators, selects, function arguments) is bounded: a file of
  // thousands of "(" must be an error, not a stack overflow.
  struct Nest {
    explicit Nest(ExpressionParser& p) : p_(p) {
      if (++p_.nesting_ > kMaxDepth) p_.fail("nested too deeply");
    }
    ~Nest() { --p_.nesting_; }
    ExpressionParser& p_;
  };

  void select() {
    const Nest nest(*this);
    logic_or();
    if (accept("?")) {
      select();
      expect(":");
      select();
      emit(Op::kSelect);
    }
  }
  void logic_or() {
    logic_and();
    while (accept("||")) {
      logic_and();
      emit(Op::kOr);
    }
  }
  void logic_and() {
    comparison();
    while (accept("&&")) {
      comparison();
      emit(Op::kAnd);
    }
  }
  void comparison() {
    sum();
    static constexpr std::array<std::pair<const char*, Op>, 6> kOps = {{
        {"==", Op::kEq}, {"!=", Op::kNe}, {"<=", Op::kLe}, {">=", Op::kGe}, {"<", Op::kLt},
        {">", Op::kGt}}};
    for (const auto& [token, op] : kOps) {
      if (accept(token)) {
        sum();
        emit(op);
        skip_space();
        for (const auto& [other, unused] : kOps) {
          (void)unused;
          if (s_.compare(pos_, std::char_traits<char>::length(other), other) == 0)
            fail("comparisons do not chain: use && between them");
        }
        return;
      }
    }
  }
  void sum() {
    product();
    for (;;) {
      if (accept("+")) {
        product();
        emit(Op::kAdd);
      } else if (accept("-")) {
        product();
        emit(Op::kSub);
      } else {
        return;
      }
    }
  }
  void product() {
    unary();
    for (;;) {
      if (accept("*")) {
        unary();
        emit(Op::kMul);
      } else if (accept("/")) {
        unary();
        emit(Op::kDiv);
      } else {
        return;
      }
    }
  }
  void unary() {
    const Nest nest(*this);
    if (accept("!")) {
      unary();
      emit(Op::kNot);
    } else if (accept("-")) {
      unary();
      emit(Op::kNeg);
    } else {
      primary();
    }
  }
  std::string identifier() {
    const std::size_t start = pos_;
    while (pos_ < s_.size() &&
           (std::isalnum(static_cast<unsigned char>(s_[pos_])) || s_[pos_] == '_'))
      ++pos_;
    return s_.substr(start, pos_ - start);
  }
  void primary() {
    skip_space();
    if (pos_ >= s_.size()) fail("expected a value");
    const char c = s_[pos_];
    if (accept("(")) {
      select();
      expect(")");
      return;
    }
    if (std::isdigit(static_cast<unsigned char>(c)) || c == '.') {
      const char* begin = s_.c_str() + pos_;
      char* end = nullptr;
      const double v = std::strtod(begin, &end);
      if (end == begin || !std::isfinite(v)) fail("bad number");
      pos_ += static_cast<std::size_t>(end - begin);
      if (pos_ < s_.size() && (std::isalpha(static_cast<unsigned char>(s_[pos_])) || s_[pos_] == '_'))
        fail("bad number");
      emit(Op::kConst, v);
      return;
    }
    if (!(std::isalpha(static_cast<unsigned char>(c)) || c == '_')) fail("expected a value");
    const int column = static_cast<int>(pos_) + 1;
    const std::string word = identifier();
    if (word == "true" || word == "false") {
      emit(Op::kConst, word == "true" ? 1.0 : 0.0);
      return;
    }
    skip_space();
    if (pos_ < s_.size() && s_[pos_] == '(') {
      call(word, column);
      return;
    }
    Name name{word, "", column};
    if (pos_ < s_.size() && s_[pos_] == '.') {
      ++pos_;
      name.member = identifier();
      if (name.member.empty()) fail("expected a name after '.'");
    }
    out_.names_.push_back(name);
    emit(Op::kLoad, 0.0, static_cast<int>(out_.names_.size()) - 1);
  }
  void call(const std::string& function, int column) {
    struct Function {
      const char* name;
      int arity;
      Op op;
    };
    static constexpr std::array<Function, 7> kFunctions = {{
        {"min", 2, Op::kMin}, {"max", 2, Op::kMax}, {"clamp", 3, Op::kClamp}, {"abs", 1, Op::kAbs},
        {"round", 1, Op::kRound}, {"floor", 1, Op::kFloor}, {"mod", 2, Op::kMod}}};
    const Function* f = nullptr;
    for (const Function& candidate : kFunctions)
      if (function == candidate.name) f = &candidate;
    if (f == nullptr)
      throw ExpressionError(column, "no function '" + function +
                                        "' (min, max, clamp, abs, round, floor, mod)");
    expect("(");
    for (int i = 0; i < f->arity; ++i) {
      if (i > 0) expect(",");
      select();
    }
    if (!accept(")"))
      throw ExpressionError(column, function + " takes " + std::to_string(f->arity) +
                                        (f->arity == 1 ? " argument" : " arguments"));
    emit(f->op);
  }

  Expression& out_;
  const std::string& s_;
  std::size_t pos_ = 0;
  int nesting_ = 0;
};

Expression Expression::parse(const std::string& text) {
  Expression e;
  e.text_ = text;
  ExpressionParser(e).parse();
  return e;
}

Expression Expression::constant(double value) {
  Expression e;
  e.text_ = std::to_string(value);
  e.code_.push_back({Op::kConst, value, -1});
  e.bound_ = true;
  e.max_depth_ = 1;
  return e;
}

std::vector<Name> Expression::names() const { return names_; }

void Expression::bind(const NameResolver& resolve) {
  refs_.clear();
  for (const Name& n : names_) refs_.push_back(resolve(n));
  bound_ = true;
}

namespace {
double truth(bool b) { return b ? 1.0 : 0.0; }
}  // namespace

double Expression::evaluate(const RefReader& reader) const {
  if (!bound_) throw std::logic_error("expression '" + text_ + "' evaluated before it was bound");
  std::array<double, ExpressionParser::kMaxDepth> stack{};
  int top = -1;  // index of the top value
  for (const Instr& i : code_) {
    switch (i.op) {
      case Op::kConst: stack[static_cast<std::size_t>(++top)] = i.value; continue;
      case Op::kLoad:
        stack[static_cast<std::size_t>(++top)] = reader.read(refs_[static_cast<std::size_t>(i.name)]);
        continue;
      default: break;
    }
    double& a1 = stack[static_cast<std::size_t>(top)];
    switch (i.op) {  // one argument, in place
      case Op::kNot: a1 = truth(a1 == 0.0); continue;
      case Op::kNeg: a1 = -a1; continue;
      case Op::kAbs: a1 = std::abs(a1); continue;
      case Op::kRound: a1 = std::round(a1); continue;
      case Op::kFloor: a1 = std::floor(a1); continue;
      default: break;
    }
    if (i.op == Op::kSelect || i.op == Op::kClamp) {
      const double c = stack[static_cast<std::size_t>(top)];
      const double b = stack[static_cast<std::size_t>(top - 1)];
      double& a = stack[static_cast<std::size_t>(top - 2)];
      a = i.op == Op::kSelect ? (a != 0.0 ? b : c) : std::clamp(a, std::min(b, c), std::max(b, c));
      top -= 2;
      continue;
    }
    const double b = stack[static_cast<std::size_t>(top)];
    double& a = stack[static_cast<std::size_t>(--top)];
    switch (i.op) {
      case Op::kOr: a = truth(a != 0.0 || b != 0.0); break;
      case Op::kAnd: a = truth(a != 0.0 && b != 0.0); break;
      case Op::kEq: a = truth(a == b); break;
      case Op::kNe: a = truth(a != b); break;
      case Op::kLt: a = truth(a < b); break;
      case Op::kLe: a = truth(a <= b); break;
      case Op::kGt: a = truth(a > b); break;
      case Op::kGe: a = truth(a >= b); break;
      case Op::kAdd: a = a + b; break;
      case Op::kSub: a = a - b; break;
      case Op::kMul: a = a * b; break;
      case Op::kDiv: a = b == 0.0 ? 0.0 : a / b; break;
      case Op::kMin: a = std::min(a, b); break;
      case Op::kMax: a = std::max(a, b); break;
      case Op::kMod: a = b == 0.0 ? 0.0 : a - b * std::floor(a / b); break;
      default: break;
    }
  }
  const double v = stack[0];
  return std::isfinite(v) ? v : 0.0;
}

}  // namespace vcockpit::systems
