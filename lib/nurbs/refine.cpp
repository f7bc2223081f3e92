#include "nurbs/refine.hpp"

#include "core/error.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace iga::nurbs {

namespace {

/// A univariate B-spline in homogeneous form: knots U, degree p, control
/// points Pw (n+1 rows of (w P, w)).
struct HomogeneousCurve {
    int p = 0;
    std::vector<double> U;
    Matrix Pw;
};

/// A5.4 RefineKnotVectCurve: inserts the sorted values X (each inside the
/// domain) into U. Exact: the new basis spans the old one.
HomogeneousCurve refine_knot_vector(const HomogeneousCurve& curve, const KnotVector& knots,
                                    const std::vector<double>& X)
{
    const int p = curve.p;
    const std::vector<double>& U = curve.U;
    const Matrix& Pw = curve.Pw;
    const int n = static_cast<int>(Pw.rows()) - 1;
    const int m = n + p + 1;
    const int r = static_cast<int>(X.size()) - 1;
    if (r < 0)
        return curve;
    HomogeneousCurve out;
    out.p = p;
    out.U.assign(m + r + 2, 0.0);
    out.Pw.resize(n + r + 2, Pw.cols());
    std::vector<double>& Ubar = out.U;
    Matrix& Qw = out.Pw;

    const int a = knots.find_span(X[0]);
    const int b = knots.find_span(X[r]) + 1;
    for (int j = 0; j <= a - p; ++j)
        Qw.row(j) = Pw.row(j);
    for (int j = b - 1; j <= n; ++j)
        Qw.row(j + r + 1) = Pw.row(j);
    for (int j = 0; j <= a; ++j)
        Ubar[j] = U[j];
    for (int j = b + p; j <= m; ++j)
        Ubar[j + r + 1] = U[j];
    int i = b + p - 1;
    int k = b + p + r;
    for (int j = r; j >= 0; --j) {
        while (X[j] <= U[i] && i > a) {
            Qw.row(k - p - 1) = Pw.row(i - p - 1);
            Ubar[k] = U[i];
            --k;
            --i;
        }
        Qw.row(k - p - 1) = Qw.row(k - p);
        for (int l = 1; l <= p; ++l) {
            const int ind = k - p + l;
            double alpha = Ubar[k + l] - X[j];
            if (alpha == 0.0) {
                Qw.row(ind - 1) = Qw.row(ind);
            } else {
                alpha /= Ubar[k + l] - U[i - p + l];
                Qw.row(ind - 1) = alpha * Qw.row(ind - 1) + (1.0 - alpha) * Qw.row(ind);
            }
        }
        Ubar[k] = X[j];
        --k;
    }
    return out;
}

double binomial(int n, int k)
{
    double b = 1.0;
    for (int i = 1; i <= k; ++i)
        b = b * (n - k + i) / i;
    return b;
}

/// A5.9 DegreeElevateCurve: raises the degree by t. Each span is made a Bezier
/// segment by knot insertion, elevated with the Bezier coefficients, and the
/// knots inserted for that are removed again, so continuity is kept.
HomogeneousCurve elevate_degree_curve(const HomogeneousCurve& curve, int t)
{
    const int p = curve.p;
    const std::vector<double>& U = curve.U;
    const Matrix& Pw = curve.Pw;
    const int dim = static_cast<int>(Pw.cols());
    const int n = static_cast<int>(Pw.rows()) - 1;
    const int m = n + p + 1;
    const int ph = p + t;
    const int ph2 = ph / 2;

    // Bezier degree elevation coefficients bezalfs(i, j) = C(p,j) C(t,i-j) / C(ph,i).
    Matrix bezalfs = Matrix::Zero(ph + 1, p + 1);
    bezalfs(0, 0) = 1.0;
    bezalfs(ph, p) = 1.0;
    for (int i = 1; i <= ph2; ++i) {
        const double inv = 1.0 / binomial(ph, i);
        for (int j = std::max(0, i - t); j <= std::min(p, i); ++j)
            bezalfs(i, j) = inv * binomial(p, j) * binomial(t, i - j);
    }
    for (int i = ph2 + 1; i <= ph - 1; ++i)
        for (int j = std::max(0, i - t); j <= std::min(p, i); ++j)
            bezalfs(i, j) = bezalfs(ph - i, p - j);

    // Upper bounds: every distinct interior knot gains t, the ends gain t each.
    const int max_knots = m + 1 + t * (m + 1);
    HomogeneousCurve out;
    out.p = ph;
    out.U.assign(max_knots, 0.0);
    out.Pw = Matrix::Zero(max_knots, dim);
    std::vector<double>& Uh = out.U;
    Matrix& Qw = out.Pw;

    Matrix bpts(p + 1, dim), ebpts(ph + 1, dim), next_bpts(std::max(p - 1, 1), dim);
    std::vector<double> alfs(std::max(p - 1, 1));

    int mh = ph, kind = ph + 1, r = -1, a = p, b = p + 1, cind = 1;
    double ua = U[0];
    Qw.row(0) = Pw.row(0);
    for (int i = 0; i <= ph; ++i)
        Uh[i] = ua;
    for (int i = 0; i <= p; ++i)
        bpts.row(i) = Pw.row(i);

    while (b < m) {
        int i = b;
        while (b < m && U[b] == U[b + 1])
            ++b;
        const int mul = b - i + 1;
        mh += mul + t;
        const double ub = U[b];
        const int oldr = r;
        r = p - mul;
        const int lbz = oldr > 0 ? (oldr + 2) / 2 : 1;
        const int rbz = r > 0 ? ph - (r + 1) / 2 : ph;
        if (r > 0) {
            // Insert ub r times to close the current Bezier segment.
            const double numer = ub - ua;
            for (int k = p; k > mul; --k)
                alfs[k - mul - 1] = numer / (U[a + k] - ua);
            for (int j = 1; j <= r; ++j) {
                const int save = r - j;
                const int s = mul + j;
                for (int k = p; k >= s; --k)
                    bpts.row(k) = alfs[k - s] * bpts.row(k) + (1.0 - alfs[k - s]) * bpts.row(k - 1);
                next_bpts.row(save) = bpts.row(p);
            }
        }
        // Elevate the Bezier segment; only points lbz..ph are used below.
        for (int i2 = lbz; i2 <= ph; ++i2) {
            ebpts.row(i2).setZero();
            for (int j = std::max(0, i2 - t); j <= std::min(p, i2); ++j)
                ebpts.row(i2) += bezalfs(i2, j) * bpts.row(j);
        }
        if (oldr > 1) {
            // Remove the knot ua oldr times (it was inserted for the previous segment).
            int first = kind - 2;
            int last = kind;
            const double den = ub - ua;
            const double bet = (ub - Uh[kind - 1]) / den;
            for (int tr = 1; tr < oldr; ++tr) {
                int i3 = first, j = last, kj = j - kind + 1;
                while (j - i3 > tr) {
                    if (i3 < cind) {
                        const double alf = (ub - Uh[i3]) / (ua - Uh[i3]);
                        Qw.row(i3) = alf * Qw.row(i3) + (1.0 - alf) * Qw.row(i3 - 1);
                    }
                    if (j >= lbz) {
                        if (j - tr <= kind - ph + oldr) {
                            const double gam = (ub - Uh[j - tr]) / den;
                            ebpts.row(kj) = gam * ebpts.row(kj) + (1.0 - gam) * ebpts.row(kj + 1);
                        } else {
                            ebpts.row(kj) = bet * ebpts.row(kj) + (1.0 - bet) * ebpts.row(kj + 1);
                        }
                    }
                    ++i3;
                    --j;
                    --kj;
                }
                --first;
                ++last;
            }
        }
        if (a != p)  // load the knot ua
            for (int i4 = 0; i4 < ph - oldr; ++i4)
                Uh[kind++] = ua;
        for (int j = lbz; j <= rbz; ++j)
            Qw.row(cind++) = ebpts.row(j);
        if (b < m) {
            for (int j = 0; j < r; ++j)
                bpts.row(j) = next_bpts.row(j);
            for (int j = r; j <= p; ++j)
                bpts.row(j) = Pw.row(b - p + j);
            a = b;
            ++b;
            ua = ub;
        } else {
            for (int i5 = 0; i5 <= ph; ++i5)
                Uh[kind + i5] = ub;
        }
    }
    const int nh = mh - ph - 1;
    out.U.resize(mh + 1);
    out.Pw.conservativeResize(nh + 1, dim);
    return out;
}

/// Applies a univariate homogeneous operation to every row of the control net
/// along direction `dir` (all combinations of the other indices), and builds
/// the new patch from the results.
template <class Operation>
Patch apply_along(const Patch& patch, int dir, Operation&& operation)
{
    const int n = patch.n_par();
    const int d = patch.dim();
    std::array<int, 3> counts{1, 1, 1};
    for (int k = 0; k < n; ++k)
        counts[k] = patch.n_basis(k);

    // Homogeneous control points (w P, w).
    auto homogeneous_row = [&](int index) {
        Eigen::RowVectorXd row(d + 1);
        const double w = patch.weights()(index);
        row.head(d) = w * patch.control_points().row(index);
        row(d) = w;
        return row;
    };

    HomogeneousCurve line;
    line.p = patch.degree(dir);
    line.U = patch.knots(dir).knot_values();
    line.Pw.resize(counts[dir], d + 1);

    std::vector<HomogeneousCurve> results;
    // Loop over the other two directions (o1 slower than o0 is irrelevant here:
    // results are addressed by ijk below).
    std::array<int, 2> others{0, 0};
    for (int k = 0, m = 0; k < 3; ++k)
        if (k != dir)
            others[m++] = k;
    const int n0 = counts[others[0]], n1 = counts[others[1]];
    results.reserve(static_cast<std::size_t>(n0) * n1);
    for (int j1 = 0; j1 < n1; ++j1)
        for (int j0 = 0; j0 < n0; ++j0) {
            std::array<int, 3> ijk{0, 0, 0};
            ijk[others[0]] = j0;
            ijk[others[1]] = j1;
            for (int i = 0; i < counts[dir]; ++i) {
                ijk[dir] = i;
                line.Pw.row(i) = homogeneous_row(patch.control_point_index(ijk));
            }
            results.push_back(operation(line));
        }

    const HomogeneousCurve& first = results.front();
    std::vector<KnotVector> knots = patch.all_knots();
    knots[dir] = KnotVector(first.p, first.U);
    std::array<int, 3> new_counts = counts;
    new_counts[dir] = static_cast<int>(first.Pw.rows());
    const int n_cp = new_counts[0] * new_counts[1] * new_counts[2];
    RowMatrix points(n_cp, d);
    Vector weights(n_cp);
    for (int j1 = 0; j1 < n1; ++j1)
        for (int j0 = 0; j0 < n0; ++j0) {
            const HomogeneousCurve& result = results[static_cast<std::size_t>(j1) * n0 + j0];
            for (int i = 0; i < new_counts[dir]; ++i) {
                std::array<int, 3> ijk{0, 0, 0};
                ijk[others[0]] = j0;
                ijk[others[1]] = j1;
                ijk[dir] = i;
                const int index = ijk[0] + new_counts[0] * (ijk[1] + new_counts[1] * ijk[2]);
                const double w = result.Pw(i, d);
                weights(index) = w;
                points.row(index) = result.Pw.row(i).head(d) / w;
            }
        }
    return Patch(std::move(knots), std::move(points), std::move(weights));
}

void check_direction(const Patch& patch, int dir, const char* what)
{
    IGA_CHECK(dir >= 0 && dir < patch.n_par(), std::string(what) + ": direction " + std::to_string(dir) +
                                                   " does not exist on a patch with " +
                                                   std::to_string(patch.n_par()) + " parametric directions");
}

}  // namespace

Patch insert_knots(const Patch& patch, int dir, const std::vector<double>& values)
{
    check_direction(patch, dir, "insert_knots");
    if (values.empty())
        return patch;
    const KnotVector& knots = patch.knots(dir);
    std::vector<double> X = values;
    std::sort(X.begin(), X.end());
    for (const double x : X)
        IGA_CHECK(std::isfinite(x) && x > knots.front() && x < knots.back(),
                  "insert_knots: value " + std::to_string(x) + " is not strictly inside the parameter domain");
    for (std::size_t i = 0; i < X.size();) {
        std::size_t j = i;
        while (j < X.size() && X[j] == X[i])
            ++j;
        const int multiplicity = knots.multiplicity(X[i]) + static_cast<int>(j - i);
        IGA_CHECK(multiplicity <= knots.degree(), "insert_knots: knot " + std::to_string(X[i]) +
                                                      " would reach multiplicity " + std::to_string(multiplicity) +
                                                      " > degree " + std::to_string(knots.degree()));
        i = j;
    }
    return apply_along(patch, dir, [&](const HomogeneousCurve& line) { return refine_knot_vector(line, knots, X); });
}

Patch elevate_degree(const Patch& patch, int dir, int times)
{
    check_direction(patch, dir, "elevate_degree");
    IGA_CHECK(times >= 0, "elevate_degree: times must be >= 0");
    if (times == 0)
        return patch;
    return apply_along(patch, dir, [&](const HomogeneousCurve& line) { return elevate_degree_curve(line, times); });
}

Patch refine_uniform(const Patch& patch, int dir, int n_spans)
{
    check_direction(patch, dir, "refine_uniform");
    IGA_CHECK(n_spans >= 1, "refine_uniform: n_spans must be >= 1");
    const KnotVector& knots = patch.knots(dir);
    const double front = knots.front();
    const double back = knots.back();
    // A grid value counts as present when it matches a knot to round-off of the
    // domain length, so that re-refining a refined patch does not add slivers.
    const double same_knot = 1e-12 * (back - front);
    std::vector<double> values;
    const std::vector<double> breaks = knots.breakpoints();
    for (int k = 1; k < n_spans; ++k) {
        const double u = front + (back - front) * k / n_spans;
        const bool present = std::any_of(breaks.begin(), breaks.end(),
                                         [&](double b) { return std::abs(b - u) <= same_knot; });
        if (!present)
            values.push_back(u);
    }
    return insert_knots(patch, dir, values);
}

Patch halve_spans(const Patch& patch, int times)
{
    IGA_CHECK(times >= 0, "halve_spans: times must be >= 0");
    Patch refined = patch;
    for (int dir = 0; dir < refined.n_par(); ++dir)
        for (int t = 0; t < times; ++t) {
            const std::vector<double> breaks = refined.knots(dir).breakpoints();
            std::vector<double> midpoints;
            for (std::size_t k = 0; k + 1 < breaks.size(); ++k)
                midpoints.push_back(0.5 * (breaks[k] + breaks[k + 1]));
            refined = insert_knots(refined, dir, midpoints);
        }
    return refined;
}

std::vector<Eigen::MatrixXd> bezier_extraction(const KnotVector& knots)
{
    // Borden, Scott, Evans, Hughes (2011), Algorithm 1, 0-based. C_e maps the
    // Bernstein basis of element e to its p+1 B-spline functions: N^e = C_e B.
    const int p = knots.degree();
    const std::vector<double>& U = knots.knot_values();
    const int m = static_cast<int>(U.size());
    std::vector<Eigen::MatrixXd> C;
    C.reserve(knots.n_spans());
    C.push_back(Eigen::MatrixXd::Identity(p + 1, p + 1));
    std::vector<double> alphas(p + 1);
    int a = p;       // index of the left knot of the current element
    int b = a + 1;   // scans to the right end of the current element
    while (b < m - 1) {
        C.push_back(Eigen::MatrixXd::Identity(p + 1, p + 1));
        const int i = b;
        while (b < m - 1 && U[b + 1] == U[b])
            ++b;
        const int mult = b - i + 1;
        if (mult < p) {
            const double numer = U[b] - U[a];
            for (int j = p; j > mult; --j)
                alphas[j - mult - 1] = numer / (U[a + j] - U[a]);
            const int r = p - mult;
            Eigen::MatrixXd& current = C[C.size() - 2];
            Eigen::MatrixXd& next = C.back();
            for (int j = 1; j <= r; ++j) {
                const int save = r - j;
                const int s = mult + j;
                for (int k = p; k >= s; --k) {
                    const double alpha = alphas[k - s];
                    current.col(k) = alpha * current.col(k) + (1.0 - alpha) * current.col(k - 1);
                }
                if (b < m - 1)  // the overlapping block of the next element
                    next.block(save, save, j + 1, 1) = current.block(p - j, p, j + 1, 1);
            }
        }
        if (b < m - 1) {
            a = b;
            ++b;
        }
    }
    // The loop appends one operator too many (for the right end).
    C.pop_back();
    IGA_ASSERT(static_cast<int>(C.size()) == knots.n_spans(), "one extraction operator per span");
    return C;
}

RowMatrix bezier_control_points(const Patch& patch, const Element& element)
{
    std::array<std::vector<Eigen::MatrixXd>, 3> extraction;
    for (int k = 0; k < patch.n_par(); ++k)
        extraction[static_cast<std::size_t>(k)] = bezier_extraction(patch.knots(k));
    return bezier_control_points(patch, element, extraction);
}

RowMatrix bezier_control_points(const Patch& patch, const Element& element,
                                const std::array<std::vector<Eigen::MatrixXd>, 3>& extraction)
{
    const int n = patch.n_par();
    const int d = patch.dim();
    std::array<Eigen::MatrixXd, 3> C;
    std::array<int, 3> n_local{1, 1, 1};
    for (int k = 0; k < 3; ++k) {
        if (k < n) {
            C[k] = extraction[static_cast<std::size_t>(k)][static_cast<std::size_t>(
                patch.knots(k).span_number(element.span[static_cast<std::size_t>(k)]))];
            n_local[k] = patch.degree(k) + 1;
        } else {
            C[k] = Eigen::MatrixXd::Ones(1, 1);
        }
    }
    const int n_points = n_local[0] * n_local[1] * n_local[2];
    // Q^b = (C_w kron C_v kron C_u)^T (w P, w)^e, then project.
    Matrix Pw(n_points, d + 1);
    int a = 0;
    for (int k = 0; k < n_local[2]; ++k)
        for (int j = 0; j < n_local[1]; ++j)
            for (int i = 0; i < n_local[0]; ++i, ++a) {
                std::array<int, 3> ijk{i, j, k};
                for (int q = 0; q < n; ++q)
                    ijk[q] += element.span[q] - patch.degree(q);
                const int index = patch.control_point_index(ijk);
                const double w = patch.weights()(index);
                Pw.row(a).head(d) = w * patch.control_points().row(index);
                Pw(a, d) = w;
            }
    Matrix Qw = Matrix::Zero(n_points, d + 1);
    for (int c = 0; c < n_points; ++c) {  // Bezier point (ci, cj, ck)
        const int ci = c % n_local[0], cj = (c / n_local[0]) % n_local[1], ck = c / (n_local[0] * n_local[1]);
        for (int s = 0; s < n_points; ++s) {  // local B-spline point (si, sj, sk)
            const int si = s % n_local[0], sj = (s / n_local[0]) % n_local[1], sk = s / (n_local[0] * n_local[1]);
            const double factor = C[0](si, ci) * C[1](sj, cj) * C[2](sk, ck);
            if (factor != 0.0)
                Qw.row(c) += factor * Pw.row(s);
        }
    }
    RowMatrix out(n_points, d);
    for (int c = 0; c < n_points; ++c)
        out.row(c) = Qw.row(c).head(d) / Qw(c, d);
    return out;
}

}  // namespace iga::nurbs
