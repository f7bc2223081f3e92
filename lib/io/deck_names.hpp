#pragma once
// The deck spellings of the enums of io/deck.hpp: the one string <-> enum table,
// used by the reader (parsing) and the writer (the resolved deck).
//
// Spellings equal the enumerator names and the words of
// docs/deck.md. Side names live in core/side.hpp.

#include "io/deck.hpp"

#include <array>
#include <string_view>

namespace iga::io {

template <class E>
struct EnumName {
    std::string_view name;
    E value;
};

/// DeckNames<E>::all lists every enumerator of E with its deck spelling.
template <class E>
struct DeckNames;

template <>
struct DeckNames<PlaneMode> {
    static constexpr std::array<EnumName<PlaneMode>, 2> all{{{"strain", PlaneMode::strain},
                                                             {"stress", PlaneMode::stress}}};
};

template <>
struct DeckNames<Kinematics> {
    static constexpr std::array<EnumName<Kinematics>, 2> all{{{"small", Kinematics::small},
                                                              {"finite", Kinematics::finite}}};
};

template <>
struct DeckNames<MaterialModel> {
    static constexpr std::array<EnumName<MaterialModel>, 3> all{
        {{"linear_elastic", MaterialModel::linear_elastic},
         {"saint_venant_kirchhoff", MaterialModel::saint_venant_kirchhoff},
         {"neo_hookean", MaterialModel::neo_hookean}}};
};

template <>
struct DeckNames<SolverBackend> {
    static constexpr std::array<EnumName<SolverBackend>, 2> all{{{"suitesparse", SolverBackend::suitesparse},
                                                                 {"petsc", SolverBackend::petsc}}};
};

template <>
struct DeckNames<SolverType> {
    static constexpr std::array<EnumName<SolverType>, 2> all{{{"direct", SolverType::direct},
                                                              {"iterative", SolverType::iterative}}};
};

template <>
struct DeckNames<Formulation> {
    static constexpr std::array<EnumName<Formulation>, 2> all{{{"two_half_pass", Formulation::two_half_pass},
                                                               {"single_pass", Formulation::single_pass}}};
};

template <>
struct DeckNames<Enforcement> {
    static constexpr std::array<EnumName<Enforcement>, 2> all{
        {{"penalty", Enforcement::penalty}, {"augmented_lagrangian", Enforcement::augmented_lagrangian}}};
};
template <>
struct DeckNames<LawType> {
    static constexpr std::array<EnumName<LawType>, 2> all{
        {{"penalty", LawType::penalty}, {"exponential", LawType::exponential}}};
};

template <>
struct DeckNames<ShapeType> {
    static constexpr std::array<EnumName<ShapeType>, 5> all{{{"half_disc", ShapeType::half_disc},
                                                             {"quarter_disc", ShapeType::quarter_disc},
                                                             {"rectangle", ShapeType::rectangle},
                                                             {"sphere_octant", ShapeType::sphere_octant},
                                                             {"box", ShapeType::box}}};
};

template <>
struct DeckNames<AccuracyQuantity> {
    static constexpr std::array<EnumName<AccuracyQuantity>, 4> all{
        {{"pressure_l2", AccuracyQuantity::pressure_l2},
         {"force", AccuracyQuantity::force},
         {"contact_radius", AccuracyQuantity::contact_radius},
         {"stick_zone", AccuracyQuantity::stick_zone}}};
};

template <>
struct DeckNames<ReferenceType> {
    static constexpr std::array<EnumName<ReferenceType>, 4> all{
        {{"hertz_cylinder_plane", ReferenceType::hertz_cylinder_plane},
         {"hertz_two_cylinders", ReferenceType::hertz_two_cylinders},
         {"hertz_sphere_plane", ReferenceType::hertz_sphere_plane},
         {"hertz_two_spheres", ReferenceType::hertz_two_spheres}}};
};

/// A load's kind is the key that holds its value (`traction: [0, -1]`).
template <>
struct DeckNames<LoadKind> {
    static constexpr std::array<EnumName<LoadKind>, 4> all{{{"traction", LoadKind::traction},
                                                            {"force", LoadKind::force},
                                                            {"pressure", LoadKind::pressure},
                                                            {"gravity", LoadKind::gravity}}};
};

/// The keys of the steps of a `transform:` list, in the order of the
/// alternatives of io::TransformStep (index() selects the key).
inline constexpr std::array<std::string_view, 4> transform_step_keys{"translate", "rotate", "mirror", "scale"};
static_assert(std::variant_size_v<TransformStep> == transform_step_keys.size());

/// The deck spelling of an enumerator ("linear_elastic", ...).
template <class E>
constexpr std::string_view deck_name(E value)
{
    for (const auto& entry : DeckNames<E>::all)
        if (entry.value == value)
            return entry.name;
    return "?";
}

}  // namespace iga::io
