#include "case/expression.hpp"

#include <cctype>
#include <cstdint>
#include <functional>
#include <cmath>
#include <cstring>
#include <map>
#include <sstream>
#include <tuple>
#include <unordered_map>

#include "core/error.hpp"

namespace quadapt {

// ============================================================================ builders

namespace {

Expr make(ExprOp op, double value, std::vector<Expr> args) {
  auto n = std::make_shared<ExprNode>();
  n->op = op;
  n->value = value;
  n->args = std::move(args);
  return n;
}

bool is_const(const Expr& e) { return e->op == ExprOp::Const; }
bool is_const(const Expr& e, double v) { return e->op == ExprOp::Const && e->value == v; }

double apply_unary(ExprOp op, double a) {
  switch (op) {
    case ExprOp::Neg: return -a;
    case ExprOp::Sin: return std::sin(a);
    case ExprOp::Cos: return std::cos(a);
    case ExprOp::Tan: return std::tan(a);
    case ExprOp::Exp: return std::exp(a);
    case ExprOp::Log: return std::log(a);
    case ExprOp::Sqrt: return std::sqrt(a);
    case ExprOp::Tanh: return std::tanh(a);
    case ExprOp::Sinh: return std::sinh(a);
    case ExprOp::Cosh: return std::cosh(a);
    case ExprOp::Atan: return std::atan(a);
    case ExprOp::Abs: return std::abs(a);
    case ExprOp::Sign: return a > 0 ? 1.0 : (a < 0 ? -1.0 : 0.0);
    default: return 0;
  }
}

double apply_binary(ExprOp op, double a, double b) {
  switch (op) {
    case ExprOp::Add: return a + b;
    case ExprOp::Sub: return a - b;
    case ExprOp::Mul: return a * b;
    case ExprOp::Div: return a / b;
    case ExprOp::Pow: return std::pow(a, b);
    default: return 0;
  }
}

bool is_binary(ExprOp op) {
  return op == ExprOp::Add || op == ExprOp::Sub || op == ExprOp::Mul || op == ExprOp::Div ||
         op == ExprOp::Pow;
}

}  // namespace

Expr expr_const(double v) { return make(ExprOp::Const, v, {}); }

Expr expr_var(int axis) { return make(axis == 0 ? ExprOp::X : ExprOp::Y, 0, {}); }

Expr expr_unary(ExprOp op, Expr a) {
  if (is_const(a)) return expr_const(apply_unary(op, a->value));
  if (op == ExprOp::Neg && a->op == ExprOp::Neg) return a->args[0];
  return make(op, 0, {std::move(a)});
}

Expr expr_binary(ExprOp op, Expr a, Expr b) {
  if (is_const(a) && is_const(b)) return expr_const(apply_binary(op, a->value, b->value));
  switch (op) {
    case ExprOp::Add:
      if (is_const(a, 0)) return b;
      if (is_const(b, 0)) return a;
      if (b->op == ExprOp::Neg) return expr_binary(ExprOp::Sub, a, b->args[0]);
      break;
    case ExprOp::Sub:
      if (is_const(b, 0)) return a;
      if (is_const(a, 0)) return expr_unary(ExprOp::Neg, b);
      if (b->op == ExprOp::Neg) return expr_binary(ExprOp::Add, a, b->args[0]);
      break;
    case ExprOp::Mul:
      if (is_const(a, 0) || is_const(b, 0)) return expr_const(0);
      if (is_const(a, 1)) return b;
      if (is_const(b, 1)) return a;
      if (is_const(a, -1)) return expr_unary(ExprOp::Neg, b);
      if (is_const(b, -1)) return expr_unary(ExprOp::Neg, a);
      break;
    case ExprOp::Div:
      if (is_const(a, 0)) return expr_const(0);
      if (is_const(b, 1)) return a;
      break;
    case ExprOp::Pow:
      if (is_const(b, 1)) return a;
      if (is_const(b, 0)) return expr_const(1);
      break;
    default: break;
  }
  return make(op, 0, {std::move(a), std::move(b)});
}

// ============================================================================ parser

namespace {

const std::map<std::string, ExprOp>& functions() {
  static const std::map<std::string, ExprOp> f = {
      {"sin", ExprOp::Sin},   {"cos", ExprOp::Cos},   {"tan", ExprOp::Tan},
      {"exp", ExprOp::Exp},   {"log", ExprOp::Log},   {"sqrt", ExprOp::Sqrt},
      {"tanh", ExprOp::Tanh}, {"sinh", ExprOp::Sinh}, {"cosh", ExprOp::Cosh},
      {"atan", ExprOp::Atan}, {"abs", ExprOp::Abs}};
  return f;
}

struct Token {
  enum Kind { Number, Name, Symbol, End } kind = End;
  std::string text;
  double value = 0;
  int column = 0;  // 1-based
};

class Parser {
 public:
  explicit Parser(const std::string& src) : src_(src) { tokenize(); }

  Expr parse() {
    if (tokens_.size() == 1) fail(tokens_[0], "empty expression");
    Expr e = expr();
    if (peek().kind != Token::End) fail(peek(), "unexpected token (missing operator?)");
    return e;
  }

 private:
  const std::string& src_;
  std::vector<Token> tokens_;
  size_t pos_ = 0;

  [[noreturn]] void fail(const Token& t, const std::string& what, const std::string& hint = "") const {
    std::ostringstream os;
    os << "column " << t.column << ": " << what;
    if (t.kind == Token::End)
      os << " at the end";
    else
      os << " near '" << t.text << "'";
    os << hint << " in: " << src_;
    throw InputError(os.str());
  }

  void tokenize() {
    const size_t n = src_.size();
    size_t i = 0;
    while (i < n) {
      unsigned char ch = static_cast<unsigned char>(src_[i]);
      if (std::isspace(ch)) { ++i; continue; }
      Token t;
      t.column = static_cast<int>(i) + 1;
      if (std::isdigit(ch) || (ch == '.' && i + 1 < n && std::isdigit(static_cast<unsigned char>(src_[i + 1])))) {
        size_t j = i;
        while (j < n && std::isdigit(static_cast<unsigned char>(src_[j]))) ++j;
        if (j < n && src_[j] == '.') {
          ++j;
          while (j < n && std::isdigit(static_cast<unsigned char>(src_[j]))) ++j;
        }
        // Exponent only when 'e'/'E' is followed by digits (optionally signed): "2e" is 2 then e.
        if (j < n && (src_[j] == 'e' || src_[j] == 'E')) {
          size_t k = j + 1;
          if (k < n && (src_[k] == '+' || src_[k] == '-')) ++k;
          if (k < n && std::isdigit(static_cast<unsigned char>(src_[k]))) {
            while (k < n && std::isdigit(static_cast<unsigned char>(src_[k]))) ++k;
            j = k;
          }
        }
        t.kind = Token::Number;
        t.text = src_.substr(i, j - i);
        t.value = std::strtod(t.text.c_str(), nullptr);
        i = j;
      } else if (std::isalpha(ch) || ch == '_') {
        size_t j = i;
        while (j < n && (std::isalnum(static_cast<unsigned char>(src_[j])) || src_[j] == '_')) ++j;
        t.kind = Token::Name;
        t.text = src_.substr(i, j - i);
        i = j;
      } else if (std::strchr("+-*/^(),", ch)) {
        t.kind = Token::Symbol;
        t.text = std::string(1, static_cast<char>(ch));
        ++i;
      } else {
        t.kind = Token::Symbol;
        t.text = std::string(1, static_cast<char>(ch));
        fail(t, "invalid character");
      }
      tokens_.push_back(t);
    }
    Token end;
    end.kind = Token::End;
    end.column = static_cast<int>(n) + 1;
    tokens_.push_back(end);
  }

  const Token& peek() const { return tokens_[pos_]; }
  const Token& next() { return tokens_[pos_++]; }
  bool accept(const char* sym) {
    if (peek().kind == Token::Symbol && peek().text == sym) { ++pos_; return true; }
    return false;
  }
  void expect(const char* sym, const char* what) {
    if (accept(sym)) return;
    // "50(x + 1)", "2 x": an operand or '(' where an operator belongs (no implicit multiplication)
    const Token& t = peek();
    const bool operand = std::string(sym) == ")" && (t.kind == Token::Number || t.kind == Token::Name ||
                                                     (t.kind == Token::Symbol && t.text == "("));
    fail(t, std::string("expected ") + what + (operand ? " (missing operator? write 50*(x + 1), not 50(x + 1))" : ""));
  }

  Expr expr() {
    Expr e = term();
    for (;;) {
      if (accept("+")) e = expr_binary(ExprOp::Add, e, term());
      else if (accept("-")) e = expr_binary(ExprOp::Sub, e, term());
      else return e;
    }
  }
  Expr term() {
    Expr e = unary();
    for (;;) {
      if (accept("*")) e = expr_binary(ExprOp::Mul, e, unary());
      else if (accept("/")) e = expr_binary(ExprOp::Div, e, unary());
      else return e;
    }
  }
  Expr unary() {
    if (accept("-")) return expr_unary(ExprOp::Neg, unary());
    if (accept("+")) return unary();
    return power();
  }
  Expr power() {
    Expr base = primary();
    if (accept("^")) return expr_binary(ExprOp::Pow, base, unary());
    return base;
  }
  Expr primary() {
    const Token& t = peek();
    if (t.kind == Token::Number) { next(); return expr_const(t.value); }
    if (t.kind == Token::Symbol && t.text == "(") {
      next();
      Expr e = expr();
      expect(")", "')'");
      return e;
    }
    if (t.kind == Token::Name) {
      next();
      if (t.text == "x") return expr_var(0);
      if (t.text == "y") return expr_var(1);
      if (t.text == "pi") return expr_const(M_PI);
      if (t.text == "e") return expr_const(M_E);
      if (t.text == "pow") {
        expect("(", "'(' after pow");
        Expr a = expr();
        expect(",", "',' (pow takes two arguments)");
        Expr b = expr();
        expect(")", "')'");
        return expr_binary(ExprOp::Pow, a, b);
      }
      auto f = functions().find(t.text);
      if (f != functions().end()) {
        expect("(", ("'(' after " + t.text).c_str());
        Expr a = expr();
        expect(")", "')'");
        return expr_unary(f->second, a);
      }
      fail(t, "unknown name",
           " (variables x, y; constants pi, e; functions sin cos tan exp log sqrt tanh sinh cosh atan abs pow)");
    }
    if (t.kind == Token::End) fail(t, "expression ends unexpectedly");
    if (t.text == "*") fail(t, "unexpected token", " (powers are written x^2 or pow(x, 2), not x**2)");
    fail(t, "unexpected token");
  }
};

}  // namespace

Expr parse_expression(const std::string& source) { return Parser(source).parse(); }

double parse_constant(const std::string& source) {
  Expr e = parse_expression(source);
  if (depends_on_xy(e)) throw InputError("must be a constant (no x or y) in: " + source);
  return evaluate(e, 0, 0);
}

// ============================================================================ calculus

namespace {

struct Differentiator {
  int axis;
  std::unordered_map<const ExprNode*, Expr> memo;

  Expr d(const Expr& e) {
    auto it = memo.find(e.get());
    if (it != memo.end()) return it->second;
    Expr r = compute(e);
    memo.emplace(e.get(), r);
    return r;
  }

  Expr compute(const Expr& e) {
    auto C = expr_const;
    auto U = expr_unary;
    auto B = expr_binary;
    using O = ExprOp;
    switch (e->op) {
      case O::Const: return C(0);
      case O::X: return C(axis == 0 ? 1 : 0);
      case O::Y: return C(axis == 1 ? 1 : 0);
      default: break;
    }
    const Expr& a = e->args[0];
    Expr da = d(a);
    if (is_binary(e->op)) {
      const Expr& b = e->args[1];
      Expr db = d(b);
      switch (e->op) {
        case O::Add: return B(O::Add, da, db);
        case O::Sub: return B(O::Sub, da, db);
        case O::Mul: return B(O::Add, B(O::Mul, da, b), B(O::Mul, a, db));
        case O::Div:  // a'/b - a b'/b^2
          return B(O::Sub, B(O::Div, da, b), B(O::Div, B(O::Mul, a, db), B(O::Mul, b, b)));
        case O::Pow:
          if (is_const(b)) {  // b a^(b-1) a'
            return B(O::Mul, B(O::Mul, b, B(O::Pow, a, C(b->value - 1))), da);
          }
          if (is_const(a)) {  // a^b log(a) b'
            return B(O::Mul, B(O::Mul, e, C(std::log(a->value))), db);
          }
          // a^b (b' log a + b a'/a)
          return B(O::Mul, e, B(O::Add, B(O::Mul, db, U(O::Log, a)), B(O::Div, B(O::Mul, b, da), a)));
        default: break;
      }
    }
    if (is_const(da, 0) && e->op != O::Sign) return C(0);
    switch (e->op) {
      case O::Neg: return U(O::Neg, da);
      case O::Sin: return B(O::Mul, U(O::Cos, a), da);
      case O::Cos: return U(O::Neg, B(O::Mul, U(O::Sin, a), da));
      case O::Tan: return B(O::Mul, B(O::Add, C(1), B(O::Mul, e, e)), da);
      case O::Exp: return B(O::Mul, e, da);
      case O::Log: return B(O::Div, da, a);
      case O::Sqrt: return B(O::Div, da, B(O::Mul, C(2), e));
      case O::Tanh: return B(O::Mul, B(O::Sub, C(1), B(O::Mul, e, e)), da);
      case O::Sinh: return B(O::Mul, U(O::Cosh, a), da);
      case O::Cosh: return B(O::Mul, U(O::Sinh, a), da);
      case O::Atan: return B(O::Div, da, B(O::Add, C(1), B(O::Mul, a, a)));
      case O::Abs: return B(O::Mul, U(O::Sign, a), da);
      case O::Sign: return C(0);
      default: break;
    }
    return C(0);
  }
};

}  // namespace

Expr differentiate(const Expr& e, int axis) {
  Differentiator dd{axis, {}};
  return dd.d(e);
}

double evaluate(const Expr& e, double x, double y) {
  switch (e->op) {
    case ExprOp::Const: return e->value;
    case ExprOp::X: return x;
    case ExprOp::Y: return y;
    default: break;
  }
  if (is_binary(e->op)) return apply_binary(e->op, evaluate(e->args[0], x, y), evaluate(e->args[1], x, y));
  return apply_unary(e->op, evaluate(e->args[0], x, y));
}

bool depends_on_xy(const Expr& e) {
  if (e->op == ExprOp::X || e->op == ExprOp::Y) return true;
  for (const Expr& a : e->args)
    if (depends_on_xy(a)) return true;
  return false;
}

int expr_size(const Expr& e) {
  int n = 1;
  for (const Expr& a : e->args) n += expr_size(a);
  return n;
}

std::string to_string(const Expr& e) {
  static const std::map<ExprOp, const char*> names = {
      {ExprOp::Sin, "sin"},   {ExprOp::Cos, "cos"},   {ExprOp::Tan, "tan"},   {ExprOp::Exp, "exp"},
      {ExprOp::Log, "log"},   {ExprOp::Sqrt, "sqrt"}, {ExprOp::Tanh, "tanh"}, {ExprOp::Sinh, "sinh"},
      {ExprOp::Cosh, "cosh"}, {ExprOp::Atan, "atan"}, {ExprOp::Abs, "abs"},   {ExprOp::Sign, "sign"}};
  switch (e->op) {
    case ExprOp::Const: {
      std::ostringstream os;
      os.precision(17);
      os << e->value;
      return os.str();
    }
    case ExprOp::X: return "x";
    case ExprOp::Y: return "y";
    case ExprOp::Neg: return "(-" + to_string(e->args[0]) + ")";
    case ExprOp::Add: return "(" + to_string(e->args[0]) + " + " + to_string(e->args[1]) + ")";
    case ExprOp::Sub: return "(" + to_string(e->args[0]) + " - " + to_string(e->args[1]) + ")";
    case ExprOp::Mul: return "(" + to_string(e->args[0]) + " * " + to_string(e->args[1]) + ")";
    case ExprOp::Div: return "(" + to_string(e->args[0]) + " / " + to_string(e->args[1]) + ")";
    case ExprOp::Pow: return "(" + to_string(e->args[0]) + " ^ " + to_string(e->args[1]) + ")";
    default: return std::string(names.at(e->op)) + "(" + to_string(e->args[0]) + ")";
  }
}

// ============================================================================ compiled program

ExprProgram::ExprProgram(const std::vector<Expr>& outputs) {
  std::map<std::tuple<int, std::uint64_t, int, int>, int> table;  // structural hash-consing
  std::unordered_map<const ExprNode*, int> seen;
  auto add = [&](ExprOp op, double value, int a, int b) {
    std::uint64_t bits;
    std::memcpy(&bits, &value, sizeof bits);
    auto key = std::make_tuple(static_cast<int>(op), bits, a, b);
    auto it = table.find(key);
    if (it != table.end()) return it->second;
    Instr in{op, a, b, value, false};
    if (op == ExprOp::Pow && code_[b].op == ExprOp::Const) {
      double k = code_[b].value;
      if (k == std::floor(k) && std::abs(k) <= 8) {
        in.int_pow = true;
        in.value = k;
      }
    }
    int id = static_cast<int>(code_.size());
    code_.push_back(in);
    table.emplace(key, id);
    return id;
  };
  std::function<int(const Expr&)> visit = [&](const Expr& e) -> int {
    auto it = seen.find(e.get());
    if (it != seen.end()) return it->second;
    int a = -1, b = -1;
    if (!e->args.empty()) a = visit(e->args[0]);
    if (e->args.size() > 1) b = visit(e->args[1]);
    int id = add(e->op, e->op == ExprOp::Const ? e->value : 0.0, a, b);
    seen.emplace(e.get(), id);
    return id;
  };
  for (const Expr& e : outputs) outputs_.push_back(visit(e));
}

void ExprProgram::eval(double x, double y, double* out, double* s) const {
  const int n = static_cast<int>(code_.size());
  for (int i = 0; i < n; ++i) {
    const Instr& in = code_[i];
    double r;
    switch (in.op) {
      case ExprOp::Const: r = in.value; break;
      case ExprOp::X: r = x; break;
      case ExprOp::Y: r = y; break;
      case ExprOp::Add: r = s[in.a] + s[in.b]; break;
      case ExprOp::Sub: r = s[in.a] - s[in.b]; break;
      case ExprOp::Mul: r = s[in.a] * s[in.b]; break;
      case ExprOp::Div: r = s[in.a] / s[in.b]; break;
      case ExprOp::Pow:
        if (in.int_pow) {
          int k = static_cast<int>(in.value);
          double base = s[in.a];
          if (k < 0) { base = 1.0 / base; k = -k; }
          r = 1.0;
          for (int j = 0; j < k; ++j) r *= base;
        } else {
          r = std::pow(s[in.a], s[in.b]);
        }
        break;
      default: r = apply_unary(in.op, s[in.a]); break;
    }
    s[i] = r;
  }
  for (size_t k = 0; k < outputs_.size(); ++k) out[k] = s[outputs_[k]];
}

std::vector<double> ExprProgram::eval(double x, double y) const {
  std::vector<double> scratch(code_.size()), out(outputs_.size());
  eval(x, y, out.data(), scratch.data());
  return out;
}

}  // namespace quadapt
