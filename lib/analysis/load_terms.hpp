#pragma once
// The external loads and the weak springs as model terms (analysis/term.hpp):
//   dead loads        r -= sum_k a_k(t) f_k                 (added by the root rank)
//   follower pressure r -= a(t) f_p(u),  K -= a(t) df_p/du   (finite kinematics; per side element)
//   weak springs      r += S_a u_a,      K += S_a            (free rigid-body modes,
//                                                           analysis/free_modes.hpp)
// Dead and follower loads count in the force scale (ModelAssembly::external_norm);
// the springs do not. A spring is added by the rank that owns the first element
// block holding its node, so each is added once over the ranks.

#include "analysis/free_modes.hpp"
#include "analysis/term.hpp"

#include <vector>

namespace iga::analysis {

class DeadLoadTerm final : public Term {
public:
    explicit DeadLoadTerm(const Scene& scene) : scene_(scene) {}
    void add_to(ModelAssembly& a) override;

private:
    const Scene& scene_;
};

class FollowerPressureTerm final : public Term {
public:
    explicit FollowerPressureTerm(const FollowerPressure& follower) : follower_(follower) {}
    void add_to(ModelAssembly& a) override;

private:
    const FollowerPressure& follower_;
};

class WeakSpringTerm final : public Term {
public:
    WeakSpringTerm(const Scene& scene, std::vector<NodeSpring> springs);
    void add_to(ModelAssembly& a) override;
    /// 1/2 sum_a u_a^T S_a u_a at a state (all dofs).
    double energy(const Vector& u_full) const;

private:
    std::vector<NodeSpring> springs_;
    std::vector<char> mine_;  ///< per spring: this rank adds it
};

}  // namespace iga::analysis
