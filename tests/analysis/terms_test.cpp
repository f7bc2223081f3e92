// The model as terms (analysis/term.hpp): each term's tangent is the derivative of
// its own residual (checked along random directions by central differences, under
// finite kinematics where every term depends on u), and the system's residual and
// tangent are the sums of its terms'.

#include "analysis/contact_term.hpp"
#include "analysis/elastic_term.hpp"
#include "analysis/load_terms.hpp"
#include "analysis/scene.hpp"
#include "analysis/system.hpp"
#include "io/deck_reader.hpp"
#include "support/tolerance.hpp"

#include "run_support.hpp"

#include <gtest/gtest.h>

#include <memory>
#include <random>

namespace iga::analysis {
namespace {

// Central differences with h = 1e-8 of the model size on displacements of 2e-3 of
// it: round-off eps |r| / h against |K v| ~ |r| / |u| is ~ 2e-11, truncation smaller;
// so small a step also makes it unlikely that a Gauss point's gap changes sign within
// it (the penalty law has a kink at g = 0). The bound keeps a wide margin.
constexpr double fd_step = 1e-8;
constexpr double fd_tolerance = 1e-6;
// Sums in another order (term by term against all at once): round-off only.
constexpr double sum_order_tolerance = 1e-12;

struct TermValue {
    Vector residual;      ///< free dofs
    SparseMatrix tangent; ///< free dofs
};

/// One term alone at u_free (load factor t), with its tangent.
TermValue evaluate_term(Scene& scene, Term& term, const Vector& u_free, double t)
{
    const Vector u_full = scene.dofs->expand(u_free, t);
    ModelAssembly a(scene, u_full, t, true);
    term.prepare(a);
    TermValue out;
    scene.pattern->shape(out.tangent);
    a.tangent = &out.tangent;
    a.r_full = Vector::Zero(scene.dofs->n_full());
    a.magnitude = Vector::Zero(scene.dofs->n_full());
    a.f_int = Vector::Zero(scene.dofs->n_full());
    term.add_to(a);
    EXPECT_TRUE(a.ok) << a.message;
    out.residual = scene.dofs->restrict(a.r_full);
    return out;
}

/// A state with contact active: the first body pushed `push` along -y, plus a smooth
/// strain of 1e-3 (u_x += 1e-3 x y, u_y += 5e-4 x^2: every term is then nonlinear in u,
/// and no element of a graded mesh inverts, as random noise would make them).
Vector pressed_state(const Scene& scene, double push)
{
    const assembly::DofMap& dofs = *scene.dofs;
    Vector u_free = Vector::Zero(dofs.n_free());
    for (std::size_t b = 0; b < scene.bodies.size(); ++b)
        for (int a = 0; a < scene.bodies[b].n_nodes; ++a) {
            const double x = scene.bodies[b].node_points(a, 0), y = scene.bodies[b].node_points(a, 1);
            const double u[2] = {1e-3 * x * y, (b == 0 ? -push : 0.0) + 5e-4 * x * x};
            for (int i = 0; i < 2; ++i) {
                const int f = dofs.free_index(dofs.dof(dofs.node_offset(static_cast<int>(b)) + a, i));
                if (f >= 0)
                    u_free(f) = u[i];
            }
        }
    return u_free;
}

void expect_tangent_is_the_derivative(Scene& scene, Term& term, const Vector& u, const char* name)
{
    constexpr double t = 1.0;
    const TermValue at_u = evaluate_term(scene, term, u, t);
    std::mt19937 random(11);
    std::normal_distribution<double> gauss;
    for (int trial = 0; trial < 3; ++trial) {
        Vector v(u.size());
        for (Index k = 0; k < v.size(); ++k)
            v(k) = gauss(random);
        v.normalize();
        const double h = fd_step * scene.model_size;
        const Vector fd = (evaluate_term(scene, term, u + h * v, t).residual -
                           evaluate_term(scene, term, u - h * v, t).residual) / (2.0 * h);
        const Vector Kv = at_u.tangent * v;
        const double scale = std::max(Kv.norm(), 1e-300);
        EXPECT_TRUE(test::near((Kv - fd).norm() / scale, 0.0, fd_tolerance)) << name << ", direction " << trial;
    }
}

Scene finite_scene(const std::string& deck_path, const std::vector<std::string>& overrides)
{
    std::vector<std::string> all = overrides;
    all.push_back("analysis.kinematics=finite");
    return build_scene(io::read_deck(test::source_path(deck_path), all));
}

TEST(Terms, EachTangentIsTheDerivativeOfItsResidualOnACylinderUnderPressureAgainstAPlane)
{
    // A follower pressure on the flat side instead of the deck's dead force.
    Scene scene = finite_scene("inputs/hertz.yaml", {"loads=[{body: cylinder, side: v1, pressure: 20.0}]"});
    ASSERT_EQ(scene.followers.size(), 1U);
    ASSERT_EQ(scene.pairs.size(), 1U);
    const Vector u = pressed_state(scene, 2e-3);
    RunContext context(nullptr, Verbosity::quiet);
    ElasticTerm elastic(scene, context, 1);
    FollowerPressureTerm follower(scene.followers.front());
    ContactTerm contact(scene, 0);
    expect_tangent_is_the_derivative(scene, elastic, u, "elastic bodies");
    expect_tangent_is_the_derivative(scene, follower, u, "follower pressure");
    expect_tangent_is_the_derivative(scene, contact, u, "contact against a rigid plane");
    // Contact is active at that state, so the check above saw a contact tangent.
    EXPECT_GT(evaluate_term(scene, contact, u, 1.0).residual.norm(), 0.0);
}

TEST(Terms, TheTwoHalfPassTermsTangentIsTheDerivativeOfItsResidual)
{
    Scene scene = finite_scene("inputs/hertz_two_cylinders_2d.yaml", {});
    ASSERT_EQ(scene.pairs.size(), 1U);
    // The upper cylinder (the first body) pushed down into the lower one.
    const Vector u = pressed_state(scene, 2e-3);
    ContactTerm contact(scene, 0);
    EXPECT_GT(evaluate_term(scene, contact, u, 1.0).residual.norm(), 0.0);
    expect_tangent_is_the_derivative(scene, contact, u, "two-half-pass contact");
}

TEST(Terms, TheSystemIsTheSumOfItsTerms)
{
    Scene scene = finite_scene("inputs/hertz.yaml", {"loads=[{body: cylinder, side: v1, pressure: 20.0}]"});
    const Vector u = pressed_state(scene, 2e-3);
    RunContext context(nullptr, Verbosity::quiet);
    SceneSystem system(scene, context, 1);
    solver::Evaluation whole;
    system.evaluate(u, 1.0, true, whole);
    ASSERT_TRUE(whole.ok) << whole.message;

    ElasticTerm elastic(scene, context, 1);
    DeadLoadTerm dead(scene);
    FollowerPressureTerm follower(scene.followers.front());
    ContactTerm contact(scene, 0);
    Vector r = Vector::Zero(u.size());
    SparseMatrix K;
    for (Term* term : std::vector<Term*>{&elastic, &dead, &follower, &contact}) {
        const TermValue value = evaluate_term(scene, *term, u, 1.0);
        r += value.residual;
        K = K.size() == 0 ? value.tangent : SparseMatrix(K + value.tangent);
    }
    EXPECT_TRUE(test::near((r - whole.residual).norm(), 0.0, sum_order_tolerance * whole.force_scale));
    EXPECT_TRUE(test::near(SparseMatrix(K - whole.tangent).norm(), 0.0, sum_order_tolerance * whole.tangent.norm()));
}

}  // namespace
}  // namespace iga::analysis
