#pragma once
// Compile-time sparse multivectors: the set of basis blades present is part of
// the type (a BladeSet bitmask), the result type of every product is computed at
// compile time, and only present components are stored and multiplied. This is
// the report's run-time grade tracking (Appendix A, after Wareham's libGA) moved
// to compile time, and its `_1_t`/`_2_t` single-grade types (fn 38) made general.
//
// Operators (one table, written once; the seed's `*`, `%`, `,` was a regret, fn 35):
//   a * b   geometric product          a ^ b   outer product
//   a | b   left contraction a⌋b       ~a      reverse
//   !a      dual, a I⁻¹                 a + b, a - b, -a, s * a, a / s
// Functions: inner (symmetric |r−s| product, the report's "·"), rc, scalar_product,
// involute, conjugate, grade<k>, project<Set>, dual/undual, norm2, norm, inverse,
// sandwich.
//
// C++ precedence warning: ^ and | bind more loosely than + - == and <<.
// Always parenthesise: (a ^ b) + c, never a ^ b + c.
#include "cga/algebra/metric.hpp"

#include <array>
#include <cmath>
#include <cstddef>
#include <optional>
#include <utility>

namespace gacompare::cga {

template <class A, BladeSet S>
struct Multivector {
  using algebra = A;
  static constexpr BladeSet blades = S;
  static constexpr int size = std::popcount(S);

  std::array<double, size> c{};  // components in increasing blade order

  static constexpr bool has(unsigned blade) { return (S >> blade) & 1u; }
  // Storage slot of a blade present in S.
  static constexpr int slot(unsigned blade) {
    return std::popcount(S & ((BladeSet{1} << blade) - 1));
  }
  // Blade stored in slot k.
  static constexpr unsigned blade_at(int k) {
    BladeSet s = S;
    for (int i = 0; i < k; ++i) s &= s - 1;
    return static_cast<unsigned>(std::countr_zero(s));
  }

  // Coefficient of a basis blade (0 for a blade the type does not hold).
  template <unsigned B>
  constexpr double get() const {
    if constexpr (has(B)) return c[slot(B)]; else return 0.0;
  }
  template <unsigned B>
  constexpr double& at() {
    static_assert(has(B), "blade not present in this multivector type");
    return c[slot(B)];
  }
  // Run-time lookup, for tests and printing.
  constexpr double operator[](unsigned blade) const { return has(blade) ? c[slot(blade)] : 0.0; }
};

namespace detail {

struct Term {
  unsigned char i, j, o;  // slots in a, b and the result
  signed char sign;
  bool first;             // first term into slot o: assign instead of add
};

// Iterate the blades of a set (constexpr: these loops run in the compiler).
template <class F>
constexpr void for_each_blade(BladeSet s, F f) {
  for (; s != 0; s &= s - 1) f(static_cast<unsigned>(std::countr_zero(s)));
}

// Which blades the product of sets SA and SB can reach, kept to Keep.
template <class A>
constexpr BladeSet product_blades(Product p, BladeSet sa, BladeSet sb, BladeSet keep) {
  BladeSet r = 0;
  for_each_blade(sa, [&](unsigned a) {
    for_each_blade(sb, [&](unsigned b) {
      if (term_exists<A>(p, a, b)) r |= BladeSet{1} << (a ^ b);
    });
  });
  return r & keep;
}

// The multiply-add list of one product, grouped by result slot: a fully
// unrolled, branch-free kernel once the fold below expands it.
template <class A, Product P, BladeSet SA, BladeSet SB, BladeSet Keep>
struct Table {
  static constexpr BladeSet result = product_blades<A>(P, SA, SB, Keep);
  using RA = Multivector<A, SA>;
  using RB = Multivector<A, SB>;
  using RR = Multivector<A, result>;

  // Visit the terms grouped by result blade: f(a, b, o, first).
  template <class F>
  static constexpr void visit(F f) {
    for_each_blade(result, [&](unsigned o) {
      bool first = true;
      for_each_blade(SA, [&](unsigned a) {
        const unsigned b = a ^ o;
        if (((SB >> b) & 1u) && term_exists<A>(P, a, b)) {
          f(a, b, o, first);
          first = false;
        }
      });
    });
  }
  static constexpr int count() {
    int k = 0;
    visit([&](unsigned, unsigned, unsigned, bool) { ++k; });
    return k;
  }
  static constexpr int n = count();

  static constexpr std::array<Term, n> make() {
    std::array<Term, n> t{};
    int k = 0;
    visit([&](unsigned a, unsigned b, unsigned o, bool first) {
      t[k++] = Term{static_cast<unsigned char>(RA::slot(a)), static_cast<unsigned char>(RB::slot(b)),
                    static_cast<unsigned char>(RR::slot(o)), static_cast<signed char>(blade_sign<A>(a, b)),
                    first};
    });
    return t;
  }
  static constexpr std::array<Term, n> terms = make();
};

template <Term T, std::size_t NR, std::size_t NA, std::size_t NB>
constexpr void apply(std::array<double, NR>& r, const std::array<double, NA>& a,
                     const std::array<double, NB>& b) {
  const double v = a[T.i] * b[T.j];
  if constexpr (T.first) {
    if constexpr (T.sign > 0) r[T.o] = v; else r[T.o] = -v;
  } else {
    if constexpr (T.sign > 0) r[T.o] += v; else r[T.o] -= v;
  }
}

// Every term of a product table, unrolled.
template <class T, std::size_t NR, std::size_t NA, std::size_t NB, std::size_t... K>
[[gnu::always_inline]] constexpr void apply_all(std::array<double, NR>& r, const std::array<double, NA>& a,
                                                const std::array<double, NB>& b, std::index_sequence<K...>) {
  (apply<T::terms[K]>(r, a, b), ...);
}
template <class T, class MA, class MB>
[[gnu::always_inline]] constexpr auto product_inline(const MA& a, const MB& b) {
  typename T::RR r;
  apply_all<T>(r.c, a.c, b.c, std::make_index_sequence<T::n>{});
  return r;
}
template <class T, class MA, class MB>
constexpr auto product_call(const MA& a, const MB& b) {
  return product_inline<T>(a, b);
}
// Up to this many terms a product is written where it is used. GCC's
// heuristics made small products calls (a dual sphere's 5-term inner product
// was 25-28% of the cga broadphase's time in bench/broadphase_bench.cpp, the
// call costing more than the arithmetic); larger ones (a full geometric
// product's hundreds of terms) are left to them.
inline constexpr int kInlineTerms = 64;

}  // namespace detail

// The product P of a and b, keeping only the blades in Keep: sandwiches use Keep
// to skip terms that cancel identically, so no work is spent computing zeros.
template <Product P, BladeSet Keep = ~BladeSet{0}, class A, BladeSet SA, BladeSet SB>
[[gnu::always_inline]] constexpr auto product(const Multivector<A, SA>& a, const Multivector<A, SB>& b) {
  using T = detail::Table<A, P, SA, SB, Keep>;
  if constexpr (T::n <= detail::kInlineTerms) return detail::product_inline<T>(a, b);
  else return detail::product_call<T>(a, b);
}

template <class A, BladeSet SA, BladeSet SB>
constexpr auto operator*(const Multivector<A, SA>& a, const Multivector<A, SB>& b) {
  return product<Product::geometric>(a, b);
}
template <class A, BladeSet SA, BladeSet SB>
constexpr auto operator^(const Multivector<A, SA>& a, const Multivector<A, SB>& b) {
  return product<Product::outer>(a, b);
}
template <class A, BladeSet SA, BladeSet SB>
constexpr auto operator|(const Multivector<A, SA>& a, const Multivector<A, SB>& b) {
  return product<Product::left_contraction>(a, b);
}
template <class A, BladeSet SA, BladeSet SB>
constexpr auto rc(const Multivector<A, SA>& a, const Multivector<A, SB>& b) {
  return product<Product::right_contraction>(a, b);
}
template <class A, BladeSet SA, BladeSet SB>
constexpr auto inner(const Multivector<A, SA>& a, const Multivector<A, SB>& b) {
  return product<Product::inner>(a, b);
}
template <class A, BladeSet SA, BladeSet SB>
constexpr double scalar_product(const Multivector<A, SA>& a, const Multivector<A, SB>& b) {
  return product<Product::scalar, 1>(a, b).template get<0>();
}

// --- linear operations ---------------------------------------------------------------

// Keep only the blades in Keep (grade projection and friends).
template <BladeSet Keep, class A, BladeSet S>
constexpr auto project(const Multivector<A, S>& a) {
  using R = Multivector<A, S & Keep>;
  R r;
  [&]<std::size_t... K>(std::index_sequence<K...>) {
    ((r.c[K] = a.c[Multivector<A, S>::slot(R::blade_at(static_cast<int>(K)))]), ...);
  }(std::make_index_sequence<R::size>{});
  return r;
}
template <int K, class A, BladeSet S>
constexpr auto grade(const Multivector<A, S>& a) {
  return project<grades<A>({K})>(a);
}

// Put a into a type holding at least its blades (e.g. a vector into a full multivector).
template <BladeSet To, class A, BladeSet S>
constexpr Multivector<A, To> widen(const Multivector<A, S>& a) {
  static_assert((S & ~To) == 0, "widen would drop blades");
  Multivector<A, To> r;
  [&]<std::size_t... K>(std::index_sequence<K...>) {
    ((r.c[Multivector<A, To>::slot(Multivector<A, S>::blade_at(static_cast<int>(K)))] = a.c[K]), ...);
  }(std::make_index_sequence<Multivector<A, S>::size>{});
  return r;
}

namespace detail {
template <int (*Sign)(int), class A, BladeSet S>
constexpr Multivector<A, S> signed_by_grade(const Multivector<A, S>& a) {
  Multivector<A, S> r;
  [&]<std::size_t... K>(std::index_sequence<K...>) {
    ((r.c[K] = Sign(grade_of(Multivector<A, S>::blade_at(static_cast<int>(K)))) * a.c[K]), ...);
  }(std::make_index_sequence<Multivector<A, S>::size>{});
  return r;
}
template <class A, BladeSet SA, BladeSet SB, class F>
constexpr auto combine(const Multivector<A, SA>& a, const Multivector<A, SB>& b, F f) {
  using R = Multivector<A, SA | SB>;
  R r;
  for (int k = 0; k < R::size; ++k) {
    const unsigned blade = R::blade_at(k);
    r.c[k] = f(a[blade], b[blade]);
  }
  return r;
}
}  // namespace detail

template <class A, BladeSet S>
constexpr auto reverse(const Multivector<A, S>& a) { return detail::signed_by_grade<reverse_sign>(a); }
template <class A, BladeSet S>
constexpr auto operator~(const Multivector<A, S>& a) { return reverse(a); }
template <class A, BladeSet S>
constexpr auto involute(const Multivector<A, S>& a) { return detail::signed_by_grade<involute_sign>(a); }
template <class A, BladeSet S>
constexpr auto conjugate(const Multivector<A, S>& a) { return detail::signed_by_grade<conjugate_sign>(a); }

template <class A, BladeSet SA, BladeSet SB>
constexpr auto operator+(const Multivector<A, SA>& a, const Multivector<A, SB>& b) {
  return detail::combine(a, b, [](double x, double y) { return x + y; });
}
template <class A, BladeSet SA, BladeSet SB>
constexpr auto operator-(const Multivector<A, SA>& a, const Multivector<A, SB>& b) {
  return detail::combine(a, b, [](double x, double y) { return x - y; });
}
template <class A, BladeSet S>
constexpr Multivector<A, S> operator-(Multivector<A, S> a) {
  for (double& x : a.c) x = -x;
  return a;
}
template <class A, BladeSet S>
constexpr Multivector<A, S> operator*(double s, Multivector<A, S> a) {
  for (double& x : a.c) x *= s;
  return a;
}
template <class A, BladeSet S>
constexpr Multivector<A, S> operator*(const Multivector<A, S>& a, double s) { return s * a; }
template <class A, BladeSet S>
constexpr Multivector<A, S> operator/(Multivector<A, S> a, double s) {
  for (double& x : a.c) x /= s;
  return a;
}

// In-place forms, for a right-hand side whose blades the left-hand side holds.
template <class A, BladeSet S, BladeSet S2>
  requires((S2 & ~S) == 0)
constexpr Multivector<A, S>& operator+=(Multivector<A, S>& a, const Multivector<A, S2>& b) {
  for (int k = 0; k < Multivector<A, S2>::size; ++k) a.c[Multivector<A, S>::slot(Multivector<A, S2>::blade_at(k))] += b.c[k];
  return a;
}
template <class A, BladeSet S, BladeSet S2>
  requires((S2 & ~S) == 0)
constexpr Multivector<A, S>& operator-=(Multivector<A, S>& a, const Multivector<A, S2>& b) {
  for (int k = 0; k < Multivector<A, S2>::size; ++k) a.c[Multivector<A, S>::slot(Multivector<A, S2>::blade_at(k))] -= b.c[k];
  return a;
}

// A scalar as a multivector, to add to products: 1 + B.
template <class A>
constexpr Multivector<A, 1> scalar(double s) { return {{s}}; }

// --- pseudoscalar, dual --------------------------------------------------------------

template <class A>
constexpr Multivector<A, BladeSet{1} << A::pseudoscalar> pseudoscalar() { return {{1.0}}; }
// I⁻¹ = I / I² (I² is a scalar, ±1): in Cl(3,0) and Cl(4,1) alike I² = −1, so I⁻¹ = −I.
template <class A>
constexpr Multivector<A, BladeSet{1} << A::pseudoscalar> pseudoscalar_inverse() {
  static_assert(A::r == 0, "a degenerate algebra's pseudoscalar has no inverse: use its complement (pga/algebra/cl301.hpp)");
  constexpr double ii = blade_sign<A>(A::pseudoscalar, A::pseudoscalar);
  return {{1.0 / ii}};
}
// Dual A* = A I⁻¹ and its inverse A I. (The report's fig. 14 multiplies by I on
// the left; for the odd-dimensional Cl(3,0) and Cl(4,1), I commutes with every
// element, so the side does not matter; the sign convention I⁻¹ is Dorst et al.'s.)
template <class A, BladeSet S>
constexpr auto dual(const Multivector<A, S>& a) { return a * pseudoscalar_inverse<A>(); }
template <class A, BladeSet S>
constexpr auto operator!(const Multivector<A, S>& a) { return dual(a); }
template <class A, BladeSet S>
constexpr auto undual(const Multivector<A, S>& a) { return a * pseudoscalar<A>(); }

// --- norm, inverse, sandwich ---------------------------------------------------------

// ⟨a ã⟩₀: the squared norm; negative or zero for some Cl(4,1) blades
// (a dual sphere of real radius has a positive square, a conformal point zero).
template <class A, BladeSet S>
constexpr double norm2(const Multivector<A, S>& a) { return scalar_product(a, reverse(a)); }
template <class A, BladeSet S>
double norm(const Multivector<A, S>& a) { return std::sqrt(std::abs(norm2(a))); }

// Inverse of a blade or versor, ã / (a ã). nullopt when a ã vanishes relative to
// the size of a (a null blade has no inverse), never a division by zero.
template <class A, BladeSet S>
std::optional<Multivector<A, S>> inverse(const Multivector<A, S>& a) {
  const double n2 = norm2(a);
  double scale = 0;
  for (double x : a.c) scale += x * x;
  if (!(std::abs(n2) > 1e-14 * scale)) return std::nullopt;
  return reverse(a) / n2;
}

// V X Ṽ for an even versor V, kept to the blades of X: a versor preserves grade,
// so the other blades of the full product cancel identically and are never computed.
template <class A, BladeSet SV, BladeSet SX>
constexpr Multivector<A, SX> sandwich(const Multivector<A, SV>& v, const Multivector<A, SX>& x) {
  return widen<SX>(product<Product::geometric, SX>(v * x, reverse(v)));
}

}  // namespace gacompare::cga
