#include "analysis/load_terms.hpp"

#include "mechanics/loads.hpp"

namespace iga::analysis {

void DeadLoadTerm::add_to(ModelAssembly& a)
{
    if (!a.root)  // not split over the ranks
        return;
    Vector f_dead = Vector::Zero(a.r_full.size());
    for (const DeadLoad& load : scene_.dead_loads) {
        const double amplitude = load.amplitude(a.t);
        f_dead += amplitude * load.f;
        a.magnitude += std::abs(amplitude) * load.f.cwiseAbs();
    }
    a.r_full -= f_dead;
    a.external_norm += f_dead.norm();
}

void FollowerPressureTerm::add_to(ModelAssembly& a)
{
    const FollowerPressure& follower = follower_;
    const int d = a.scene.dim;
    const double amplitude = follower.amplitude(a.t);
    for (std::size_t e = 0; e < follower.side.elements.size(); ++e) {
        const int block = follower.first_block + static_cast<int>(e);
        if (!a.owns(block))
            continue;
        const auto& element_dofs = follower.element_dofs[e];
        const Matrix u_local = local_displacement(a.u_full, element_dofs, d);
        const mechanics::LocalForceTangent f = mechanics::follower_pressure(
            follower.side.elements[e], d, follower.pressure, a.scene.kinematics, u_local);
        for (std::size_t k = 0; k < element_dofs.size(); ++k) {
            a.r_full(element_dofs[k]) -= amplitude * f.f_ext(static_cast<Index>(k));
            a.magnitude(element_dofs[k]) += std::abs(amplitude) * std::abs(f.f_ext(static_cast<Index>(k)));
        }
        a.external_norm += std::abs(amplitude) * f.f_ext.norm();
        if (a.tangent && f.df_ext_du.size() > 0)
            a.add_block(block, Matrix(-amplitude * f.df_ext_du));
    }
}

WeakSpringTerm::WeakSpringTerm(const Scene& scene, std::vector<NodeSpring> springs) : springs_(std::move(springs))
{
    // The first element block holding each dof decides the rank of a spring at it.
    std::vector<int> first_block(static_cast<std::size_t>(scene.dofs->n_full()), scene.n_element_blocks);
    for (const BodyModel& body : scene.bodies)
        for (std::size_t e = body.element_dofs.size(); e-- > 0;)
            for (int dof : body.element_dofs[e]) {
                int& first = first_block[static_cast<std::size_t>(dof)];
                first = std::min(first, body.first_block + static_cast<int>(e));
            }
    for (const NodeSpring& spring : springs_)
        mine_.push_back(scene.partition.owns(first_block[static_cast<std::size_t>(spring.dofs.front())]) ? 1 : 0);
}

void WeakSpringTerm::add_to(ModelAssembly& a)
{
    const assembly::DofMap& dofs = *a.scene.dofs;
    for (std::size_t k = 0; k < springs_.size(); ++k) {
        if (!mine_[k])
            continue;
        const NodeSpring& spring = springs_[k];
        const int n = static_cast<int>(spring.dofs.size());
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j) {
                const double s = spring.stiffness(i, j);
                if (s == 0.0)
                    continue;
                const int row = spring.dofs[static_cast<std::size_t>(i)];
                const int column = spring.dofs[static_cast<std::size_t>(j)];
                a.r_full(row) += s * a.u_full(column);
                if (a.tangent)
                    a.tangent->coeffRef(dofs.free_index(row), dofs.free_index(column)) += s;
            }
    }
}

double WeakSpringTerm::energy(const Vector& u_full) const
{
    double energy = 0.0;
    for (const NodeSpring& spring : springs_) {
        VecN u(static_cast<Index>(spring.dofs.size()));
        for (std::size_t i = 0; i < spring.dofs.size(); ++i)
            u(static_cast<Index>(i)) = u_full(spring.dofs[i]);
        energy += 0.5 * u.dot(spring.stiffness * u);
    }
    return energy;
}

}  // namespace iga::analysis
