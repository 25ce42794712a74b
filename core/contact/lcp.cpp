#include "core/contact/lcp.hpp"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <Eigen/SparseCholesky>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

namespace gacompare::core::contact {

// Column by column straight from A's storage (no triplets to sort): A is
// compressed with each column's rows in order, and `place` keeps their
// order, so each column of the block comes out sorted.
Eigen::SparseMatrix<double> principal_block(const Eigen::SparseMatrix<double>& a, const std::vector<Eigen::Index>& rows,
                                            const std::vector<Eigen::Index>& place) {
  const auto n = static_cast<Eigen::Index>(rows.size());
  Eigen::Index nnz = 0;
  for (const Eigen::Index c : rows) nnz += a.outerIndexPtr()[c + 1] - a.outerIndexPtr()[c];
  Eigen::SparseMatrix<double> out(n, n);
  out.resizeNonZeros(nnz);
  Eigen::Index at = 0;
  for (Eigen::Index k = 0; k < n; ++k) {
    out.outerIndexPtr()[k] = static_cast<int>(at);
    for (Eigen::SparseMatrix<double>::InnerIterator it(a, rows[static_cast<std::size_t>(k)]); it; ++it)
      if (const Eigen::Index j = place[static_cast<std::size_t>(it.row())]; j >= 0)
        out.innerIndexPtr()[at] = static_cast<int>(j), out.valuePtr()[at] = it.value(), ++at;
  }
  out.outerIndexPtr()[n] = static_cast<int>(at);
  out.resizeNonZeros(at);
  return out;
}

namespace {

enum class State : char { free, lower, upper, fixed };  // fixed: lo = hi

// x refined towards A_FF x = r, `solve` the regularised (A_FF + δ)⁻¹ (δ taken
// away again): converges on r's part in A_FF's range; stops when it no
// longer gains (the rest lies in the null space and moves nothing).
template <class Solve>
Eigen::VectorXd refine_with(const Eigen::SparseMatrix<double>& a_ff, const Solve& solve, const Eigen::VectorXd& r,
                            Eigen::VectorXd x, double tolerance, int most_steps = 4) {
  Eigen::VectorXd residual = r - a_ff * x;  // of x, kept for the next round
  double last = residual.cwiseAbs().maxCoeff();
  for (int k = 0; k < most_steps && last > tolerance; ++k) {
    const Eigen::VectorXd y = x + solve(residual);
    Eigen::VectorXd next = r - a_ff * y;
    const double now = next.cwiseAbs().maxCoeff();
    if (!(now < 0.5 * last)) break;
    x = y, last = now, residual.swap(next);
  }
  return x;
}

// x solving A_FF x = r for the free rows F (free[i] = position in F, or −1),
// regularised by δ and refined with A_FF itself (see lcp.hpp).
//
// Given A's factor by body G (A = G Gᵀ, Blcp::G), the sparse path factorises
// the augmented system instead,
//
//   [ I     G_Fᵀ ] [u]   [ 0 ]
//   [ G_F   −D_F ] [x] = [ −r ]     (u = −G_Fᵀ x, so (A_FF + D_F) x = r),
//
// quasi-definite, so an LDLᵀ factorisation exists in any symmetric order
// (Vanderbei, "Symmetric quasi-definite matrices", 1995), as interior-point
// and OSQP-type solvers factorise their regularised KKT systems. Where rows
// share bodies many at a time, A_FF's factor fills in by the rows at each
// body squared, the augmented one by the bodies' six freedoms: on a square
// pyramid of 10 layers (4,960 rows) its factor has 254,289 entries against
// 860,992, on 15 layers 1.3 against 6.0 million. D's entries are 1e-10 of
// A's largest diagonal, so the augmented factorisation loses digits along
// the redundant rows' directions (a 1e-3 residual on the pyramid); iterative
// refinement against A_FF + D_F takes it to the direct factorisation's
// residual in three steps (measured: 1e-3, 7e-8, 6e-12, 2e-14), and stops
// there (through_augmented).
class FreeSystem {
 public:
  FreeSystem(const Eigen::SparseMatrix<double>& a, const std::vector<Eigen::Index>& rows,
             const std::vector<Eigen::Index>& free, const Eigen::VectorXd& delta, int dense_up_to,
             const Eigen::SparseMatrix<double, Eigen::RowMajor>* g = nullptr, bool by_entries = true)
      : n_(static_cast<Eigen::Index>(rows.size())), dense_(n_ <= dense_up_to), a_ff_(principal_block(a, rows, free)) {
    if (g && !dense_ && (!by_entries || augmenting_pays(*g, rows))) {
      augment(*g, rows, delta);
      return;
    }
    // A_FF + δ, with every diagonal entry (0 + δ where A_FF has none, as
    // coeffRef would insert), built in vectors, then copied into w.reg:
    // Eigen reads a SparseMatrix, and converting a Map to one on every
    // factorisation went element by element.
    Workspace& w = workspace();
    w.outer.resize(static_cast<std::size_t>(n_) + 1), w.inner.clear(), w.values.clear();
    w.inner.reserve(static_cast<std::size_t>(a_ff_.nonZeros() + n_)), w.values.reserve(static_cast<std::size_t>(a_ff_.nonZeros() + n_));
    for (Eigen::Index k = 0; k < n_; ++k) {
      const double dk = delta[rows[static_cast<std::size_t>(k)]];
      bool diagonal = false;
      w.outer[static_cast<std::size_t>(k)] = static_cast<int>(w.inner.size());
      for (Eigen::SparseMatrix<double>::InnerIterator it(a_ff_, k); it; ++it) {
        const Eigen::Index j = it.row();
        if (j > k && !diagonal) w.inner.push_back(static_cast<int>(k)), w.values.push_back(0.0 + dk), diagonal = true;
        w.inner.push_back(static_cast<int>(j)), w.values.push_back(j == k ? it.value() + dk : it.value());
        diagonal |= j == k;
      }
      if (!diagonal) w.inner.push_back(static_cast<int>(k)), w.values.push_back(0.0 + dk);
    }
    w.outer[static_cast<std::size_t>(n_)] = static_cast<int>(w.inner.size());
    if (dense_) {
      dense_ldlt_.compute(Eigen::MatrixXd(Eigen::Map<const Eigen::SparseMatrix<double>>(
          n_, n_, static_cast<Eigen::Index>(w.inner.size()), w.outer.data(), w.inner.data(), w.values.data())));
    } else {
      factor_ = &factor_of(w);
    }
  }

  bool sparse() const { return !dense_; }
  bool augmented() const { return augmented_; }

  // The regularised system's answer: (A_FF + δI) x = r.
  Eigen::VectorXd solve(const Eigen::VectorXd& r) const { return once(r); }

  // x refined towards A_FF x = r (refine_with).
  Eigen::VectorXd refine(const Eigen::VectorXd& r, Eigen::VectorXd x, double tolerance) const {
    return refine_with(a_ff_, [&](const Eigen::VectorXd& v) { return once(v); }, r, std::move(x), tolerance);
  }

 private:
  // The sparse factorisations, kept from one factorisation to the next on
  // this thread, eight of them: the ordering (AMD) and elimination tree
  // depend only on the free rows' pattern, and finding them cost as much as
  // the numeric factorisation of a 20-cube column; and a step's velocity
  // solve and its position projection usually factorise the same matrix (the
  // same rows, all free) one after the other. So a pattern met again skips
  // the analysis, and the same pattern with the same values skips the
  // factorisation too (the factor is then the very one a fresh factorisation
  // gives: the same answers, bit for bit). The velocity solve and the
  // projection alternate, with different patterns when some rows are on a
  // bound: one remembered pattern was analysed again at every step (a
  // 10-layer wall pyramid spent a quarter of its run in AMD). As a sparse
  // direct solver's symbolic analysis is reused across numeric
  // factorisations of one pattern (Davis, "Direct Methods for Sparse Linear
  // Systems", ch. 4). One FreeSystem is in use at a time on a thread
  // (solve_blcp's latest), and the entry it reads is the newest, never the
  // one replaced.
  struct Workspace {
    std::vector<int> outer, inner;  // the regularised A_FF being built
    std::vector<double> values;
    Eigen::SparseMatrix<double> reg;  // the same, when it is factorised
  };
  struct SparseFactor {
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt;
    std::vector<int> outer, inner;  // the pattern analysed
    std::vector<double> values;     // the values factorised (empty: none yet)
    std::uint64_t used = 0;         // when last used (the least recent is replaced)
  };
  static constexpr std::size_t kPatterns = 8;
  struct Cache {
    std::array<SparseFactor, kPatterns> entries;
    std::uint64_t clock = 0;
  };
  static Workspace& workspace() {
    thread_local Workspace w;
    return w;
  }
  static const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>& factor_of(Workspace& w) {
    thread_local Cache cache;
    SparseFactor* hit = nullptr;
    for (SparseFactor& e : cache.entries)
      if (e.outer == w.outer && e.inner == w.inner) hit = &e;
    const auto n = static_cast<Eigen::Index>(w.outer.size()) - 1;
    const auto matrix = [&]() -> const Eigen::SparseMatrix<double>& {
      w.reg.resize(n, n);
      w.reg.resizeNonZeros(static_cast<Eigen::Index>(w.inner.size()));
      std::ranges::copy(w.outer, w.reg.outerIndexPtr());
      std::ranges::copy(w.inner, w.reg.innerIndexPtr());
      std::ranges::copy(w.values, w.reg.valuePtr());
      return w.reg;
    };
    if (!hit) {
      hit = &*std::ranges::min_element(cache.entries, {}, &SparseFactor::used);
      hit->ldlt.analyzePattern(matrix());
      hit->outer = w.outer, hit->inner = w.inner, hit->values.clear();
    }
    // Bit for bit (−0.0 is not 0.0, and a NaN never matches), so a reused
    // factor is exactly the one a fresh factorisation would give.
    const bool same = !hit->values.empty() && hit->values.size() == w.values.size() &&
                      std::memcmp(hit->values.data(), w.values.data(), w.values.size() * sizeof(double)) == 0;
    if (!same) {
      hit->ldlt.factorize(matrix());
      hit->values = w.values;
    }
    hit->used = ++cache.clock;
    return hit->ldlt;
  }

  // The columns of G that the rows touch: each one's place among them, in
  // G's order (−1 for the others), and how many.
  static std::pair<std::vector<int>, int> touched_columns(const Eigen::SparseMatrix<double, Eigen::RowMajor>& g,
                                                          const std::vector<Eigen::Index>& rows) {
    std::vector<int> column(static_cast<std::size_t>(g.cols()), -1);
    for (const Eigen::Index i : rows)
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(g, i); it; ++it) column[static_cast<std::size_t>(it.col())] = 0;
    int c = 0;
    for (int& k : column)
      if (k == 0) k = c++;
    return {std::move(column), c};
  }

  // Whether the augmented system [I Gᵀ; G −δ] is the one to factorise: it
  // holds fewer entries than A_FF (each triangle, the diagonals included).
  // A_FF couples every two rows that share a body, so its entries grow as
  // the square of the rows at each body, G's only as their number (six
  // columns a body). A stack's faces bring four corner rows each, some
  // twenty rows to a cube of a square pyramid, and its augmented factor is
  // the cheaper (docs/collision-response.md); a pile's bodies touch a few
  // others at a point or two each, about five rows a body, and A's own
  // factor was: on a settled pile of 1,000 mixed bodies, whose solves hold
  // some 2,300 rows, the augmented one took 2.3 times as long, and each of
  // its answers is refined against A_FF in several solves besides.
  bool augmenting_pays(const Eigen::SparseMatrix<double, Eigen::RowMajor>& g, const std::vector<Eigen::Index>& rows) const {
    Eigen::Index coupling = 0;  // G_F's entries
    for (const Eigen::Index i : rows)
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(g, i); it; ++it) ++coupling;
    const Eigen::Index augmented = touched_columns(g, rows).second + n_ + coupling;  // I, −δ and G_F, one triangle
    const Eigen::Index own = (a_ff_.nonZeros() + n_) / 2;  // A_FF + δ, one triangle with its diagonal
    return augmented < own;
  }

  // The augmented system [I G_Fᵀ; G_F −D_F] in the workspace (the columns
  // of G that F's rows touch, in G's order), factorised.
  void augment(const Eigen::SparseMatrix<double, Eigen::RowMajor>& g, const std::vector<Eigen::Index>& rows,
               const Eigen::VectorXd& delta) {
    augmented_ = true;
    const auto [column, c] = touched_columns(g, rows);
    columns_ = c;
    std::vector<Eigen::Triplet<double>> t;
    t.reserve(static_cast<std::size_t>(c + n_ + 2 * 12 * n_));
    for (int k = 0; k < c; ++k) t.emplace_back(k, k, 1.0);
    for (Eigen::Index f = 0; f < n_; ++f) {
      const Eigen::Index i = rows[static_cast<std::size_t>(f)];
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(g, i); it; ++it) {
        const int k = column[static_cast<std::size_t>(it.col())];
        t.emplace_back(c + f, k, it.value()), t.emplace_back(k, c + f, it.value());
      }
      t.emplace_back(c + f, c + f, -delta[i]);
    }
    Eigen::SparseMatrix<double> k(c + n_, c + n_);
    k.setFromTriplets(t.begin(), t.end());
    Workspace& w = workspace();
    w.outer.assign(k.outerIndexPtr(), k.outerIndexPtr() + k.cols() + 1);
    w.inner.assign(k.innerIndexPtr(), k.innerIndexPtr() + k.nonZeros());
    w.values.assign(k.valuePtr(), k.valuePtr() + k.nonZeros());
    factor_ = &factor_of(w);
    regularised_ = a_ff_;
    for (Eigen::Index f = 0; f < n_; ++f) regularised_.coeffRef(f, f) += delta[rows[static_cast<std::size_t>(f)]];
    // ‖A_FF + D_F‖∞, for the refinement's stop (symmetric: its largest column sum).
    for (Eigen::Index f = 0; f < n_; ++f) {
      double sum = 0;
      for (Eigen::SparseMatrix<double>::InnerIterator it(regularised_, f); it; ++it) sum += std::abs(it.value());
      norm_ = std::max(norm_, sum);
    }
  }
  // (A_FF + D_F)⁻¹ r through the augmented factor, refined against A_FF + D_F
  // until the residual is at rounding level (a normwise backward error of at
  // most ε: |r − K x|∞ ≤ ε (‖K‖∞ |x|∞ + |r|∞), K = A_FF + D_F), or until a
  // step no longer halves it (at most eight steps). The stop at rounding
  // level is LAPACK's for its refinement (dgerfs; Higham, "Accuracy and
  // Stability of Numerical Algorithms", ch. 12). Without it every refinement
  // ran on until a step failed to halve, through steps that only stirred the
  // last digits: on the 15-layer square pyramid's landings
  // (`bench/scale/pyramid_scene.py --layers 15 --duration 0.1`, one thread)
  // the run went from 33.7 to 27.1 s, with 2,052 active-set changes against
  // 1,950 (the landings' own spread from one build to the next is ±15 %) and
  // no solve left to the sweeps' cap. At 8ε it went to 23.0 s, but the
  // degenerate pyramids of lcp_test (Blcp.DegenerateCyclesEnd) then ran
  // solves to the pivot limit: their redundant corners need those digits.
  Eigen::VectorXd through_augmented(const Eigen::VectorXd& r) const {
    const auto once_augmented = [&](const Eigen::VectorXd& v) {
      Eigen::VectorXd big = Eigen::VectorXd::Zero(columns_ + n_);
      big.tail(n_) = -v;
      return Eigen::VectorXd(factor_->solve(big).tail(n_));
    };
    Eigen::VectorXd x = once_augmented(r);
    const double rounding =
        std::numeric_limits<double>::epsilon() * (norm_ * x.cwiseAbs().maxCoeff() + r.cwiseAbs().maxCoeff());
    return refine_with(regularised_, once_augmented, r, std::move(x), rounding, 8);
  }
  Eigen::VectorXd once(const Eigen::VectorXd& r) const {
    if (augmented_) return through_augmented(r);
    return dense_ ? Eigen::VectorXd(dense_ldlt_.solve(r)) : Eigen::VectorXd(factor_->solve(r));
  }
  Eigen::Index n_;
  bool dense_;
  bool augmented_ = false;
  Eigen::Index columns_ = 0;             // G_F's columns (augmented)
  double norm_ = 0;                      // ‖A_FF + D_F‖∞ (augmented)
  Eigen::SparseMatrix<double> regularised_;  // A_FF + D_F (augmented)
  Eigen::SparseMatrix<double> a_ff_;
  Eigen::LDLT<Eigen::MatrixXd> dense_ldlt_;
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>* factor_ = nullptr;
};

// The free rows' system through one solve's active-set changes: factorised
// once, then, while few rows have changed, solved through a Schur complement
// instead of factorised again (the Schur-complement update of active-set
// methods: Gill, Murray, Saunders & Wright, "Sparse matrix methods in
// optimization", 1984; Bartlett & Biegler's QPSchur, 2006). With K0 = A + D
// on the rows F0 of the last factorisation and the free rows F now differing
// by the rows dropped (R = F0 \ F, now on a bound) and the rows added
// (S = F \ F0),
//
//   [ K0       K_F0,S   E_R ] [x0]   [r0]
//   [ K_S,F0   K_SS     0   ] [xS] = [rS]      (r0 zero on R)
//   [ E_Rᵀ     0        0   ] [μ ]   [0 ]
//
// holds the dropped rows at zero (μ takes up their equations) and gives
// x_F = (x0 off R, xS): K0's factor and the dense k × k complement
// C = [K_SS 0; 0 0] − Bᵀ K0⁻¹ B, B = [K_F0,S  E_R], k = |R| + |S|. A change
// costs one solve with K0's factor (a column of K0⁻¹ B, kept for the
// solve's later changes), where a landing stack's factorisation cost tens of
// milliseconds and its solves took up to 64 changes each. K0⁻¹ is applied to
// right-hand sides K0 itself cannot meet (a dropped corner of a face leaves
// its redundant set), so each answer is polished by one step of iterative
// refinement against K_FF. Past most_updates changes, or at most
// dense_up_to free rows (a dense factorisation that small costs about an
// update), the free rows are factorised afresh, as they were at every change
// before: there, and wherever a solve needs no change, the answers are those
// of a fresh factorisation, bit for bit.
class UpdatedSystem {
 public:
  UpdatedSystem(const Blcp& p, const Eigen::VectorXd& delta, const BlcpSettings& settings)
      : a_(p.A), g_(p.G.rows() == p.A.rows() ? &p.G : nullptr), delta_(delta), settings_(settings),
        column_of_(static_cast<std::size_t>(p.A.rows()), -1) {}

  enum class Change { factorised, updated, none };
  // The free rows now (ascending; free[i] is row i's place among them or −1).
  Change set(const std::vector<Eigen::Index>& rows, const std::vector<Eigen::Index>& free) {
    rows_ = rows, place_ = free;
    changes_.clear();
    if (base_ && base_->sparse() && static_cast<int>(rows.size()) > settings_.dense_up_to) {
      for (const Eigen::Index i : base_rows_)
        if (free[static_cast<std::size_t>(i)] < 0) changes_.push_back(i);
      for (const Eigen::Index i : rows)
        if (base_place_[static_cast<std::size_t>(i)] < 0) changes_.push_back(i);
      if (static_cast<int>(changes_.size()) <= settings_.most_updates) {
        if (changes_.empty()) return Change::none;
        update();
        return Change::updated;
      }
      changes_.clear();
    }
    for (const Eigen::Index i : cached_) column_of_[static_cast<std::size_t>(i)] = -1;
    cached_.clear(), w_.clear();
    const bool augment = g_ && static_cast<int>(rows.size()) >= settings_.augmented_from;
    base_.emplace(a_, rows, free, delta_, settings_.dense_up_to, augment ? g_ : nullptr, settings_.augment_by_entries);
    base_rows_ = rows, base_place_ = free;
    return Change::factorised;
  }

  bool augmented() const { return base_ && base_->augmented(); }

  // (A_FF + D_F) x = r for the free rows F.
  Eigen::VectorXd solve(const Eigen::VectorXd& r) const {
    if (changes_.empty()) return base_->solve(r);
    Eigen::VectorXd x = through_complement(r);
    return x + through_complement(r - a_ff_ * x - delta_(rows_).cwiseProduct(x));
  }

  // x refined towards A_FF x = r (FreeSystem::refine).
  Eigen::VectorXd refine(const Eigen::VectorXd& r, Eigen::VectorXd x, double tolerance) const {
    if (changes_.empty()) return base_->refine(r, std::move(x), tolerance);
    return refine_with(a_ff_, [&](const Eigen::VectorXd& v) { return solve(v); }, r, std::move(x), tolerance);
  }

 private:
  bool dropped(Eigen::Index i) const { return base_place_[static_cast<std::size_t>(i)] >= 0; }
  // b_iᵀ v for change i's column of B, v over F0.
  double column_dot(Eigen::Index i, const Eigen::VectorXd& v) const {
    if (dropped(i)) return v[base_place_[static_cast<std::size_t>(i)]];
    double sum = 0;
    for (Eigen::SparseMatrix<double>::InnerIterator it(a_, i); it; ++it)
      if (const Eigen::Index k = base_place_[static_cast<std::size_t>(it.row())]; k >= 0) sum += it.value() * v[k];
    return sum;
  }
  const Eigen::VectorXd& column(Eigen::Index i) {
    auto& at = column_of_[static_cast<std::size_t>(i)];
    if (at < 0) {
      Eigen::VectorXd b = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(base_rows_.size()));
      if (dropped(i)) b[base_place_[static_cast<std::size_t>(i)]] = 1;
      else
        for (Eigen::SparseMatrix<double>::InnerIterator it(a_, i); it; ++it)
          if (const Eigen::Index k = base_place_[static_cast<std::size_t>(it.row())]; k >= 0) b[k] = it.value();
      at = static_cast<Eigen::Index>(w_.size());
      w_.push_back(base_->solve(b));
      cached_.push_back(i);
    }
    return w_[static_cast<std::size_t>(at)];
  }
  void update() {
    a_ff_ = principal_block(a_, rows_, place_);
    const auto k = static_cast<Eigen::Index>(changes_.size());
    Eigen::MatrixXd c(k, k);
    for (Eigen::Index v = 0; v < k; ++v) {
      const Eigen::Index j = changes_[static_cast<std::size_t>(v)];
      const Eigen::VectorXd& w = column(j);
      for (Eigen::Index u = 0; u < k; ++u) {
        const Eigen::Index i = changes_[static_cast<std::size_t>(u)];
        const double c0 = dropped(i) || dropped(j) ? 0.0 : a_.coeff(i, j) + (i == j ? delta_[i] : 0.0);
        c(u, v) = c0 - column_dot(i, w);
      }
    }
    complement_.compute(c);
  }
  Eigen::VectorXd through_complement(const Eigen::VectorXd& r) const {
    const auto m0 = static_cast<Eigen::Index>(base_rows_.size());
    Eigen::VectorXd r0(m0);
    for (Eigen::Index k = 0; k < m0; ++k) {
      const Eigen::Index f = place_[static_cast<std::size_t>(base_rows_[static_cast<std::size_t>(k)])];
      r0[k] = f >= 0 ? r[f] : 0.0;
    }
    const Eigen::VectorXd z = base_->solve(r0);
    const auto k = static_cast<Eigen::Index>(changes_.size());
    Eigen::VectorXd t(k);
    for (Eigen::Index u = 0; u < k; ++u) {
      const Eigen::Index i = changes_[static_cast<std::size_t>(u)];
      t[u] = (dropped(i) ? 0.0 : r[place_[static_cast<std::size_t>(i)]]) - column_dot(i, z);
    }
    const Eigen::VectorXd y = complement_.solve(t);
    Eigen::VectorXd x0 = z;
    for (Eigen::Index u = 0; u < k; ++u)
      x0 -= y[u] * w_[static_cast<std::size_t>(column_of_[static_cast<std::size_t>(changes_[static_cast<std::size_t>(u)])])];
    Eigen::VectorXd x(static_cast<Eigen::Index>(rows_.size()));
    for (Eigen::Index u = 0; u < k; ++u)
      if (const Eigen::Index i = changes_[static_cast<std::size_t>(u)]; !dropped(i)) x[place_[static_cast<std::size_t>(i)]] = y[u];
    for (Eigen::Index k0 = 0; k0 < m0; ++k0)
      if (const Eigen::Index f = place_[static_cast<std::size_t>(base_rows_[static_cast<std::size_t>(k0)])]; f >= 0) x[f] = x0[k0];
    return x;
  }

  const Eigen::SparseMatrix<double>& a_;
  const Eigen::SparseMatrix<double, Eigen::RowMajor>* g_;  // A's factor by body, or none
  const Eigen::VectorXd& delta_;
  const BlcpSettings& settings_;
  std::optional<FreeSystem> base_;                       // K0's factor
  std::vector<Eigen::Index> base_rows_, base_place_;     // F0, and each row's place in it
  std::vector<Eigen::Index> rows_, place_;               // F, and each row's place in it
  std::vector<Eigen::Index> changes_;                    // R (in F0's order), then S (ascending)
  Eigen::SparseMatrix<double> a_ff_;                     // A_FF, while changes_ is not empty
  Eigen::PartialPivLU<Eigen::MatrixXd> complement_;      // C's factors
  std::vector<Eigen::Index> column_of_, cached_;         // a row's column of K0⁻¹ B in w_ (−1: none yet)
  std::vector<Eigen::VectorXd> w_;
};

double tolerance_of(const Blcp& p, const BlcpSettings& s) {
  return s.velocity_tolerance > 0 ? s.velocity_tolerance : 1e-12 * (1 + p.b.cwiseAbs().maxCoeff());
}

}  // namespace

namespace {

// blcp_residual with A's diagonal given (a lookup per row otherwise).
double residual_of(const Blcp& p, const Eigen::VectorXd& lambda, const Eigen::VectorXd& diagonal) {
  const Eigen::VectorXd w = p.A * lambda + p.b;
  double worst = 0;
  for (Eigen::Index i = 0; i < w.size(); ++i) {
    const double d = std::abs(diagonal[i]);
    worst = std::max(worst, d * std::max({0.0, p.lo[i] - lambda[i], lambda[i] - p.hi[i]}));
    const bool at_lo = lambda[i] <= p.lo[i], at_hi = lambda[i] >= p.hi[i];
    // Between the bounds w must vanish; on a bound it may point away from it.
    const double v = at_lo && at_hi ? 0.0 : at_lo ? std::max(0.0, -w[i]) : at_hi ? std::max(0.0, w[i]) : std::abs(w[i]);
    worst = std::max(worst, v);
  }
  return worst;
}

}  // namespace

Eigen::MatrixXd psd_factor(const Eigen::MatrixXd& a, int most_columns) {
  const Eigen::Index k = a.rows();
  Eigen::MatrixXd g(k, std::min<Eigen::Index>(k, most_columns));
  Eigen::VectorXd left = a.diagonal();  // the diagonal of a − G Gᵀ so far
  const double floor = 1e-14 * (k > 0 ? left.maxCoeff() : 0.0);
  Eigen::Index r = 0;
  for (; r < g.cols(); ++r) {
    Eigen::Index p = 0;
    const double top = left.maxCoeff(&p);
    if (!(top > floor)) break;
    Eigen::VectorXd c = a.col(p) - g.leftCols(r) * g.row(p).head(r).transpose();
    c /= std::sqrt(top);
    left -= c.cwiseAbs2();
    left[p] = 0;
    g.col(r) = c;
  }
  return g.leftCols(r);
}

double blcp_residual(const Blcp& p, const Eigen::VectorXd& lambda) {
  Eigen::VectorXd diagonal(p.b.size());
  for (Eigen::Index i = 0; i < diagonal.size(); ++i) diagonal[i] = p.A.coeff(i, i);
  return residual_of(p, lambda, diagonal);
}

namespace {

// The regularised objective ½ λᵀ(A + D)λ + cᵀλ.
double objective(const Blcp& p, const Eigen::VectorXd& c, const Eigen::VectorXd& delta, const Eigen::VectorXd& lambda) {
  return 0.5 * lambda.dot(p.A * lambda + delta.cwiseProduct(lambda)) + c.dot(lambda);
}

// A blocked step moves one set of rows onto their bounds (those the ratio
// test stops at), and each such change costs a factorisation: a landing
// stack, whose rows change by the dozen, took one per row. So the free
// minimiser x is also projected onto the bounds whole (every free row that
// crosses one goes onto it: a projected Newton step, as in Bertsekas 1982
// and the gradient projection of Moré & Toraldo 1991), and taken instead of
// the ratio test's step when the objective is lower there. Every step still
// lowers the objective (in exact arithmetic; the guard in active_set takes
// care of floating point), and its answer is still the free minimiser of the
// active set it ends on: the same answer, bit for bit, wherever that set is
// the same.
// `before` is λ before the ratio test's step, `lambda` after it; returns
// whether the projection was taken (lambda and state then its).
bool projected_step(const Blcp& p, const Eigen::VectorXd& c, const Eigen::VectorXd& delta,
                    const std::vector<Eigen::Index>& rows, const Eigen::VectorXd& x, const Eigen::VectorXd& before,
                    Eigen::VectorXd& lambda, std::vector<State>& state) {
  Eigen::VectorXd projected = before;
  int crossed = 0;
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const Eigen::Index i = rows[k];
    const double to = x[static_cast<Eigen::Index>(k)];
    projected[i] = std::clamp(to, p.lo[i], p.hi[i]);
    crossed += projected[i] != to;
  }
  if (crossed < 2) return false;  // one row: the ratio test's step is the same change
  if (!(objective(p, c, delta, projected) < objective(p, c, delta, lambda))) return false;
  lambda = projected;
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const Eigen::Index i = rows[k];
    const double to = x[static_cast<Eigen::Index>(k)];
    if (to < p.lo[i]) state[static_cast<std::size_t>(i)] = State::lower;
    else if (to > p.hi[i]) state[static_cast<std::size_t>(i)] = State::upper;
  }
  return true;
}

// The active-set iterations (see lcp.hpp) on the regularised problem with
// linear term c: minimise ½ λᵀ(A + D)λ + cᵀλ over the bounds, D = diag(δ),
// from λ and its rows' states. Returns whether it reached the free rows'
// minimiser with no row to release within the pivot budget; `system`,
// `rows` and `rhs` are then the last factorisation, its free rows and the
// right-hand side it solved.
bool active_set(const Blcp& p, const Eigen::VectorXd& c, const Eigen::VectorXd& delta, double tol,
                const BlcpSettings& settings, Eigen::VectorXd& lambda, std::vector<State>& state,
                std::vector<Eigen::Index>& rows, UpdatedSystem& system, Eigen::VectorXd& rhs,
                BlcpResult& result) {
  const Eigen::Index n = c.size();
  std::vector<Eigen::Index> free(static_cast<std::size_t>(n));
  // The guard against cycling (see below): the lowest objective at a release
  // so far, the rows released at the last one, and the rows held on their
  // bounds since the objective last fell.
  double lowest = INFINITY;
  std::vector<Eigen::Index> last_released;
  std::vector<char> held(static_cast<std::size_t>(n), 0);
  for (;;) {
    if (result.pivots >= settings.max_pivots) return false;
    rows.clear();
    for (Eigen::Index i = 0; i < n; ++i) {
      const bool f = state[static_cast<std::size_t>(i)] == State::free;
      free[static_cast<std::size_t>(i)] = f ? static_cast<Eigen::Index>(rows.size()) : -1;
      if (f) rows.push_back(i);
    }
    double step = 1;
    Eigen::VectorXd x, before;
    if (!rows.empty()) {
      // The free rows' minimiser with the others held: (A_FF + D_F) x = −(c_F + A_F,bound λ_bound).
      Eigen::VectorXd on_bounds = lambda;
      for (const Eigen::Index i : rows) on_bounds[i] = 0;
      const Eigen::VectorXd known = p.A * on_bounds + c;
      rhs.resize(static_cast<Eigen::Index>(rows.size()));
      for (std::size_t k = 0; k < rows.size(); ++k) rhs[static_cast<Eigen::Index>(k)] = -known[rows[k]];
      switch (system.set(rows, free)) {
        case UpdatedSystem::Change::factorised:
          ++result.factorisations;
          result.augmented += system.augmented();
          break;
        case UpdatedSystem::Change::updated: ++result.updates; break;
        case UpdatedSystem::Change::none: break;
      }
      x = system.solve(rhs);
      // The longest step towards it that keeps every free row within its bounds.
      for (std::size_t k = 0; k < rows.size(); ++k) {
        const Eigen::Index i = rows[k];
        const double from = lambda[i], to = x[static_cast<Eigen::Index>(k)];
        if (to < p.lo[i]) step = std::min(step, (from - p.lo[i]) / (from - to));
        if (to > p.hi[i]) step = std::min(step, (p.hi[i] - from) / (to - from));
      }
      step = std::max(step, 0.0);
      if (step < 1) before = lambda;
      for (std::size_t k = 0; k < rows.size(); ++k) {
        const Eigen::Index i = rows[k];
        lambda[i] += step * (x[static_cast<Eigen::Index>(k)] - lambda[i]);
      }
    }
    if (step < 1 && projected_step(p, c, delta, rows, x, before, lambda, state)) {
      ++result.pivots;
      continue;
    }
    if (step < 1) {
      // Blocked: the rows that reached a bound stay on it.
      for (std::size_t k = 0; k < rows.size(); ++k) {
        const Eigen::Index i = rows[k];
        const double to = x[static_cast<Eigen::Index>(k)];
        const double reach = 1e-12 * (std::abs(lambda[i]) + std::abs(to));
        if (to < p.lo[i] && lambda[i] <= p.lo[i] + reach) lambda[i] = p.lo[i], state[static_cast<std::size_t>(i)] = State::lower;
        if (to > p.hi[i] && lambda[i] >= p.hi[i] - reach) lambda[i] = p.hi[i], state[static_cast<std::size_t>(i)] = State::upper;
      }
      ++result.pivots;
      continue;
    }
    // At the free rows' minimiser: release every row a bound holds against
    // the gradient (w of the regularised problem); none, and this is its answer.
    //
    // In exact arithmetic the objective then falls before the next release,
    // so no active set recurs. In floating point it can stall and cycle: on
    // a pyramid's redundant corners the free solve is exact only to ~1e-11
    // in w (δ = 1e-10 of A's diagonal leaves A_FF + D_F that ill-conditioned),
    // a row released at w ≈ −4e-11 comes back below its bound (the free
    // solve gives it −2e-3), is blocked at a step of 0, and is released
    // again: the same three active sets until the pivot limit, at one
    // objective value. A rounding-level change to the solve (the augmented
    // form's refinement residual computed as A_FF x + δx rather than with
    // A_FF + D_F stored) sent 3 of 4 solves of a 6-layer pyramid's 1,024
    // rows into such cycles, and b perturbed by 1e-15 of itself 7 of 24, in
    // either factorisation (lcp_test's DegenerateCyclesEnd). So a row released at a release after which the
    // objective did not fall (by more than 1e-12 of it, the objective's own
    // rounding on a thousand rows) is held on its bound until it falls
    // again; once every row that would be released is held, the answer is
    // this one, its conditions violated only at the solve's noise (within
    // what the refinement and the proximal steps below then measure). Each
    // stalled release holds at least one more row, so the iterations end.
    // This is an anti-cycling rule in the spirit of those for degenerate
    // simplex and active-set steps (Bland 1977; Gill, Murray, Saunders &
    // Wright, "A practical anti-cycling procedure", 1989), not either of them.
    const Eigen::VectorXd w = p.A * lambda + c + delta.cwiseProduct(lambda);
    const double now = objective(p, c, delta, lambda);
    if (now < lowest - 1e-12 * std::abs(lowest) || lowest == INFINITY) {
      std::fill(held.begin(), held.end(), 0);
      lowest = std::min(lowest, now);
    } else {
      for (const Eigen::Index i : last_released) held[static_cast<std::size_t>(i)] = 1;
    }
    last_released.clear();
    for (Eigen::Index i = 0; i < n; ++i) {
      auto& st = state[static_cast<std::size_t>(i)];
      if ((st == State::lower && w[i] < -tol) || (st == State::upper && w[i] > tol)) {
        if (held[static_cast<std::size_t>(i)]) ++result.held;
        else st = State::free, last_released.push_back(i);
      }
    }
    if (last_released.empty()) return true;
    ++result.pivots;
  }
}

}  // namespace

// A feasible start: the warm start held within its bounds; a row on a bound
// starts there, every other row free. A row within 1e-12 of the largest
// impulse of its bound counts as on it: a row that ended the last step
// free at a rounding residue (a face's redundant corner, ~1e-18) started
// free, the first free solve drove it negative, and blocking it there took
// a factorisation of its own, at nearly every step of a resting pyramid
// (the ten-layer wall: 1,733 pivots in its first 2 s; 463 in all 10 s so).
// Starting it on the bound costs at most a release, which the
// conditions below make where it is needed.
std::vector<State> start(const Blcp& p, Eigen::VectorXd& lambda) {
  const Eigen::Index n = p.b.size();
  std::vector<State> state(static_cast<std::size_t>(n));
  double largest = 0;
  for (Eigen::Index i = 0; i < n; ++i) largest = std::max(largest, std::abs(lambda[i]));
  const double near = 1e-12 * largest;
  for (Eigen::Index i = 0; i < n; ++i) {
    lambda[i] = std::clamp(lambda[i], p.lo[i], p.hi[i]);
    if (lambda[i] - p.lo[i] <= near) lambda[i] = p.lo[i];
    else if (p.hi[i] - lambda[i] <= near) lambda[i] = p.hi[i];
    auto& s = state[static_cast<std::size_t>(i)];
    s = p.lo[i] == p.hi[i]       ? State::fixed
        : lambda[i] == p.lo[i]   ? State::lower
        : lambda[i] == p.hi[i]   ? State::upper
                                 : State::free;
  }
  return state;
}

// One row, a > 0: minimise ½ a λ² + b λ over lo ≤ λ ≤ hi, whose answer is
// −b/a held within the bounds; no regularisation is needed (a row alone
// is never redundant), so the answer is the problem's own, where the
// general method finds the regularised one and refines it to 1e-3 of the
// tolerance. The active-set rules are the general method's: a row that
// starts on a bound stays there while w = a λ + b points away from it to
// within the tolerance, and the counts are the changes and the (1×1)
// factorisations the general method would make. More than half the direct
// solves of a pile of boxes are of a row alone (a body touching one other
// at one point), and the general method's sparse storage and work vectors
// were most of their time.
BlcpResult one_row(const Blcp& p, Eigen::VectorXd& lambda, State s, double tol, const Eigen::VectorXd& diagonal) {
  const double a = diagonal[0], b = p.b[0], lo = p.lo[0], hi = p.hi[0];
  BlcpResult result;
  result.solved = true;
  const double w = a * lambda[0] + b;
  const bool stays = s == State::fixed || (s == State::lower && !(w < -tol)) || (s == State::upper && !(w > tol));
  if (!stays) {
    const double x = -b / a;
    const bool now_free = x > lo && x < hi;
    lambda[0] = now_free ? x : x <= lo ? lo : hi;
    result.factorisations = 1;  // a free solve: from a free start, or after the release
    result.pivots = (s == State::free ? 0 : 1) + (now_free ? 0 : 1);  // the release, and the block at a bound
  }
  result.residual = residual_of(p, lambda, diagonal);
  return result;
}

BlcpResult solve_blcp(const Blcp& p, Eigen::VectorXd& lambda, const BlcpSettings& settings) {
  const Eigen::Index n = p.b.size();
  BlcpResult result;
  if (n == 0) {
    result.solved = true;
    return result;
  }
  const double tol = tolerance_of(p, settings);
  Eigen::VectorXd diagonal(n);
  double dmax = 0;
  for (Eigen::Index i = 0; i < n; ++i) diagonal[i] = p.A.coeff(i, i), dmax = std::max(dmax, diagonal[i]);
  std::vector<State> state = start(p, lambda);
  if (n == 1 && diagonal[0] > 0 && std::isfinite(diagonal[0]) && std::isfinite(p.b[0]))
    return one_row(p, lambda, state[0], tol, diagonal);
  const Eigen::VectorXd delta =
      1e-10 * dmax * (p.weight.size() == n ? p.weight : Eigen::VectorXd(Eigen::VectorXd::Ones(n)));
  std::vector<Eigen::Index> rows;
  UpdatedSystem system(p, delta, settings);  // the free rows' last system
  Eigen::VectorXd rhs;               // and the right-hand side it solved
  Eigen::VectorXd c = p.b;           // the regularised problem's linear term
  Eigen::VectorXd best;              // the best answer so far, once a proximal step is taken
  for (int proximal = 0;; ++proximal) {
    if (!active_set(p, c, delta, tol, settings, lambda, state, rows, system, rhs, result)) {
      if (proximal > 0) lambda = best;  // (its residual is the one recorded)
      else result.residual = residual_of(p, lambda, diagonal);
      result.solved = proximal > 0;
      return result;
    }
    // The active set is the regularised problem's; the free rows' impulses
    // are refined towards the problem itself (δλ taken out of every free
    // row's velocity), kept where they stay within their bounds.
    if (!rows.empty()) {
      if (proximal > 0) {  // the problem's own right-hand side (the last solve's had c for b)
        Eigen::VectorXd on_bounds = lambda;
        for (const Eigen::Index i : rows) on_bounds[i] = 0;
        const Eigen::VectorXd known = p.A * on_bounds + p.b;
        for (std::size_t k = 0; k < rows.size(); ++k) rhs[static_cast<Eigen::Index>(k)] = -known[rows[k]];
      }
      const Eigen::VectorXd y = system.refine(rhs, lambda(rows), 1e-3 * tol);
      bool inside = true;
      for (std::size_t k = 0; k < rows.size(); ++k) {
        const double v = y[static_cast<Eigen::Index>(k)];
        inside &= v >= p.lo[rows[k]] && v <= p.hi[rows[k]];
      }
      if (inside) lambda(rows) = y;
    }
    const double residual = residual_of(p, lambda, diagonal);
    // Where the refinement would leave the bounds (the regularisation chose
    // an active set the problem itself does not: a heavily weighted row's
    // velocity is δ_i λ_i off), proximal point steps (Rockafellar 1976)
    // take δ out instead: the same regularised problem about the last
    // answer, minimise ½ λᵀAλ + bᵀλ + ½ |λ − λ_k|²_D over the bounds, whose
    // answers converge to an answer of the problem itself, each step's error
    // about δ_i / (σ + δ_i) of the last (σ the problem's curvature along it).
    // Its active set is usually the last one, so a step reuses that
    // factorisation. The steps stop once one cuts the residual by less than
    // a tenth: where the free rows' system is inconsistent (targets that no
    // rigid motion meets, to ~1e-10), the answer only drifts along a null
    // direction and the residual stays.
    if (proximal > 0 && !(residual < 0.9 * result.residual)) {
      lambda = best;
      result.solved = true;
      return result;
    }
    result.residual = residual;
    if (residual <= tol || proximal == settings.max_proximal) {
      result.solved = true;
      return result;
    }
    best = lambda;
    ++result.proximal;
    c = p.b - delta.cwiseProduct(lambda);
  }
}

}  // namespace gacompare::core::contact
