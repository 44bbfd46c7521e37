#pragma once
// Scalar expressions in x, y for manufactured solutions (docs/design.md §3): parsing, exact
// symbolic differentiation, and fast compiled evaluation.
//
// Grammar (whitespace ignored, case-sensitive):
//     expr    := term  (('+' | '-') term)*
//     term    := unary (('*' | '/') unary)*
//     unary   := ('-' | '+') unary | power
//     power   := primary ('^' unary)?            right-associative: 2^3^2 = 2^(3^2)
//     primary := NUMBER | 'x' | 'y' | 'pi' | 'e' | FUNC '(' expr ')' | 'pow' '(' expr ',' expr ')'
//              | '(' expr ')'
//     FUNC    := sin cos tan exp log sqrt tanh sinh cosh atan abs
// so -x^2 = -(x^2) and 2^-1 = 0.5. NUMBER: 12, 1.5, .5, 1e-3, 2.5E+4. log is the natural log.
//
// Differentiation is symbolic (chain rule on the tree, with constant folding and the identities
// 0+a, a*1, a*0, a^1, --a), so derivatives are exact to rounding. d|f|/dx = sign(f) f'; the
// internal function sign has derivative 0 (the distributional part at f = 0 is ignored).
//
// Errors: InputError whose message is "column C: problem near 'TOKEN' in: SOURCE" (C is 1-based),
// without a file prefix — callers (the case loader) prepend the file and key.
#include <memory>
#include <string>
#include <vector>

namespace quadapt {

/// Operation of an expression node.
enum class ExprOp {
  Const, X, Y,
  Add, Sub, Mul, Div, Pow, Neg,
  Sin, Cos, Tan, Exp, Log, Sqrt, Tanh, Sinh, Cosh, Atan, Abs, Sign
};

struct ExprNode;
/// An immutable expression tree (shared sub-trees are allowed).
using Expr = std::shared_ptr<const ExprNode>;

struct ExprNode {
  ExprOp op = ExprOp::Const;
  double value = 0;        ///< the constant (op == Const)
  std::vector<Expr> args;  ///< 1 argument (unary ops, functions) or 2 (binary ops)
};

/// Parses `source`. Throws InputError "column C: ..." on a syntax error or unknown name.
Expr parse_expression(const std::string& source);

/// Parses an expression that must not depend on x or y and returns its value (used for the
/// case file's constants, e.g. "0.01*pi/e*12"). Throws InputError on x/y or a syntax error.
double parse_constant(const std::string& source);

/// Builders with constant folding and trivial-identity simplification.
Expr expr_const(double v);
Expr expr_var(int axis);  ///< axis 0 = x, 1 = y
Expr expr_unary(ExprOp op, Expr a);
Expr expr_binary(ExprOp op, Expr a, Expr b);

/// Exact symbolic derivative d/dx (axis 0) or d/dy (axis 1).
Expr differentiate(const Expr& e, int axis);

/// Direct (slow, recursive) evaluation at (x, y).
double evaluate(const Expr& e, double x, double y);

/// Whether the expression depends on x or y.
bool depends_on_xy(const Expr& e);

/// Number of nodes of the tree (shared sub-trees counted each time they are reached).
int expr_size(const Expr& e);

/// Fully parenthesised text form, for messages and tests.
std::string to_string(const Expr& e);

/// Several expressions compiled into one straight-line program with common sub-expressions
/// shared (structural hashing): evaluating u and its derivatives together costs little more
/// than u alone. Thread-safe: eval() uses caller-provided scratch storage.
class ExprProgram {
 public:
  ExprProgram() = default;
  explicit ExprProgram(const std::vector<Expr>& outputs);

  int num_outputs() const { return static_cast<int>(outputs_.size()); }
  /// Number of distinct operations (after sharing).
  int num_slots() const { return static_cast<int>(code_.size()); }
  /// Scratch size needed by eval().
  int scratch_size() const { return num_slots(); }

  /// Evaluates every output at (x, y) into out[0..num_outputs()-1]; `scratch` must hold
  /// scratch_size() doubles (one buffer per thread).
  void eval(double x, double y, double* out, double* scratch) const;
  /// Convenience (allocates).
  std::vector<double> eval(double x, double y) const;

 private:
  struct Instr {
    ExprOp op;
    int a, b;      ///< argument slots
    double value;  ///< constant, or integer exponent for small integer powers
    bool int_pow;  ///< b is a small integer constant: use repeated multiplication
  };
  std::vector<Instr> code_;
  std::vector<int> outputs_;
};

}  // namespace quadapt
