#pragma once
// The PETSc options igacontact passes on to its PETSc backend: the deck's
// `solver.options` and the environment's PETSC_OPTIONS. Both are split into options
// here, as PETSc splits them, and checked before PETSc sees them (issue 32): an
// option may tune the linear solver, never make PETSc write or read a file, print
// its help or a log, or end the run. The deck reader (io/), the PETSc backend
// (solver/) and `igacontact study` (app/) share this check, so it lives below them.
//
// Splitting, as PETSc's PetscOptionsInsertString does it: an option is a word that
// starts with one or two dashes and a letter and is not a number ("-1" and "-inf"
// are values); the word after an option is its value unless it is an option itself.
// Words are separated by blanks (the environment: by spaces only, as PETSc splits
// it at start-up); quotes, which PETSc would read as grouping, are refused. PETSc
// compares names without regard to case, and so does this check.
//
// What passes (docs/parallel.md, "PETSc options"):
//   - the options of the linear solver's objects and of their inner solvers: names
//     starting ksp_, pc_, mat_, mg_, sub_, redundant_, fieldsplit_, telescope_,
//     redistribute_ or vec_. Everything else (logging, help, options files, memory
//     and debugging options, viewer and window settings) acts on the whole process
//     and is refused, with the reason for the well-known ones;
//   - among those, not: a name with a part that draws, dumps, saves, loads, names a
//     file or folder, prints from a library (print, verbose, logging), or loads
//     Python; MUMPS's output streams and print level (-mat_mumps_icntl_1 to 4) and
//     its out-of-core mode (icntl_22, scratch files);
//   - values: letters, digits and _ . , + - : only (no path); a value naming a
//     viewer (-ksp_view binary, -ksp_monitor ascii:log.txt, ...:hdf5, draw,
//     socket...) must print to standard output: empty, `ascii`, and the forms
//     `[ascii]:[stdout|stderr][:FORMAT]`. An option whose name has a view, monitor
//     or reason part takes no other value;
//   - numbers PETSc would take without a check: -ksp_rtol in [0, 1), -ksp_atol >= 0,
//     -ksp_divtol >= 1, all finite; -ksp_max_it in [1, 10^6], -ksp_gmres_restart in
//     [1, 1000]; -mat_mumps_icntl_N an integer, -mat_mumps_cntl_N a finite number
//     (each also under an inner solver's prefix, -mg_levels_ksp_max_it).
// An option that passes may still be one PETSc does not know, or one the chosen
// solver does not read: PetscSolver names those in the run's warnings.

#include "core/error.hpp"
#include "core/parallel.hpp"

#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace iga {

/// One option as written: "-ksp_rtol" and its value "1e-10" (or none).
struct PetscOption {
    std::string name;
    std::string value;
    bool has_value = false;

    /// "-ksp_rtol 1e-10", as written.
    std::string text() const { return has_value ? name + " " + value : name; }
};

/// Where an options text comes from: the deck's solver.options (blanks of any kind
/// separate options) or PETSC_OPTIONS (spaces only, PETSc's own reading of it).
enum class PetscOptionsSource { deck, environment };

/// The options of a text, or the first one refused and why.
struct PetscOptionsCheck {
    std::vector<PetscOption> options;
    std::string refused;  ///< the refused option as written ("-ksp_view ascii:base.yaml"), or a stray word
    std::string reason;   ///< why it is refused; empty when every option passes

    bool ok() const { return reason.empty(); }
    /// "-ksp_view ascii:base.yaml: <reason>" (empty when ok).
    std::string message() const;
};

PetscOptionsCheck check_petsc_options(std::string_view text, PetscOptionsSource source);

/// Bad input found in the PETSc options by the PETSc backend: an option refused by
/// check_petsc_options() in PETSC_OPTIONS, or a value PETSc itself rejected while it
/// set up or ran the solver. The caller locates it (solver.options in the deck, or
/// the environment variable) and reports it as a DeckError (exit 2).
class PetscOptionsError : public Error {
public:
    PetscOptionsError(PetscOptionsSource source, const std::string& reason,
                      std::string variable = "PETSC_OPTIONS")
        : Error(reason), source_(source), variable_(std::move(variable))
    {
    }
    PetscOptionsSource source() const { return source_; }
    /// The environment variable at fault (source environment): PETSC_OPTIONS, or
    /// PETSC_OPTIONS_YAML, which igacontact does not read.
    const std::string& variable() const { return variable_; }
    /// For source environment: "environment: error: VARIABLE = value: reason".
    DeckIssue environment_issue() const;

private:
    PetscOptionsSource source_;
    std::string variable_;
};

/// The options of this process's environment for PETSc, checked on every rank of
/// `comm` alike (collective): PETSC_OPTIONS_YAML must be unset or empty (PETSc would
/// read it unchecked), PETSC_OPTIONS must pass check_petsc_options(). Throws
/// PetscOptionsError (source environment, the lowest rank's reason) otherwise.
std::vector<PetscOption> checked_environment_options(const Communicator& comm = Communicator());

}  // namespace iga
