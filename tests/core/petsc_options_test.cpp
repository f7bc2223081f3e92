// Tests for core/petsc_options.hpp: the PETSc options igacontact passes on are split
// as PETSc splits them, and refused when they would make PETSc write or read a file,
// print its help or a log, or take a number it does not check (issue 32). One table
// of accepted texts, one of refused ones with the option named and the reason.

#include "core/petsc_options.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

namespace iga {
namespace {

struct Accepted {
    const char* text;
    std::size_t options;
};

const Accepted accepted[] = {
    {"", 0},
    {"-pc_type gamg -pc_gamg_threshold 0.01", 2},
    {"-ksp_monitor -ksp_converged_reason", 2},       // to standard output (sent to stderr)
    {"-ksp_view ::ascii_info_detail", 1},            // a format, no file
    {"-ksp_monitor ascii:stderr -ksp_view ascii", 2},
    {"-ksp_rtol 1e-10 -ksp_atol 0 -ksp_divtol 1e4", 3},
    {"-ksp_type gmres -ksp_gmres_restart 50 -ksp_max_it 5000", 3},
    {"-mat_mumps_icntl_14 50 -mat_mumps_cntl_1 0.01", 2},
    {"-mg_levels_ksp_max_it 3 -mg_levels_pc_type jacobi", 2},
    {"-pc_type fieldsplit -pc_fieldsplit_0_fields 0,1", 2},
    {"--ksp_rtol 1e-6", 1},                          // PETSc takes two dashes
    {"  -pc_type   jacobi  ", 1},
    {"-pc_type gamg\n-ksp_rtol 1e-9\t-ksp_monitor", 3},  // a YAML block: blanks of any kind
    {"-pc_type bogus", 1},                           // a type PETSc may not know: PETSc says so (petsc_solver)
    {"-ksp_nonexistent_option 3", 1},                // unknown to PETSc: a warning of the run (petsc_solver)
};

TEST(PetscOptions, TheSolversOptionsPass)
{
    for (const Accepted& a : accepted) {
        const PetscOptionsCheck check = check_petsc_options(a.text, PetscOptionsSource::deck);
        EXPECT_TRUE(check.ok()) << "'" << a.text << "': " << check.message();
        EXPECT_EQ(check.options.size(), a.options) << a.text;
    }
}

TEST(PetscOptions, TextIsSplitAsPetscSplitsIt)
{
    // A word after an option is its value unless it is an option itself; "-1" and
    // "-inf" are numbers, hence values (PetscOptionsValidKey).
    const PetscOptionsCheck check =
        check_petsc_options("-ksp_monitor -ksp_rtol 1e-9 -ksp_divtol 1e3 -pc_type jacobi", PetscOptionsSource::deck);
    ASSERT_TRUE(check.ok()) << check.message();
    ASSERT_EQ(check.options.size(), 4u);
    EXPECT_EQ(check.options[0].name, "-ksp_monitor");
    EXPECT_FALSE(check.options[0].has_value);
    EXPECT_EQ(check.options[1].text(), "-ksp_rtol 1e-9");
    EXPECT_EQ(check.options[3].value, "jacobi");
    const PetscOptionsCheck negative = check_petsc_options("-ksp_rtol -1", PetscOptionsSource::deck);
    EXPECT_EQ(negative.refused, "-ksp_rtol -1") << "-1 is the value, not an option";
    const PetscOptionsCheck infinite = check_petsc_options("-ksp_atol -inf", PetscOptionsSource::deck);
    EXPECT_EQ(infinite.refused, "-ksp_atol -inf");
}

struct Refused {
    const char* text;
    const char* refused;  ///< the option (or word) named
    const char* reason;   ///< a part of the reason
};

const Refused refused[] = {
    // Files written: the deck, the results, a user's file.
    {"-ksp_view ascii:base.yaml", "-ksp_view ascii:base.yaml", "PETSc would write the file base.yaml"},
    {"-mat_view binary:x", "-mat_view binary:x", "binary viewer writes a file"},
    {"-ksp_monitor ascii:file", "-ksp_monitor ascii:file", "PETSc would write the file file"},
    {"-ksp_view binary", "-ksp_view binary", "binary viewer writes a file"},
    {"-vec_view hdf5:x.h5", "-vec_view hdf5:x.h5", "hdf5 viewer writes a file"},
    {"-ksp_view draw", "-ksp_view draw", "opens a window"},
    {"-ksp_monitor stdout", "-ksp_monitor stdout", "not a viewer that prints to standard output"},
    {"-ksp_view ascii:stdout:ascii_info:append", "-ksp_view ascii:stdout:ascii_info:append", "file mode"},
    {"-ksp_view a/b", "-ksp_view a/b", "no file path"},
    {"-log_view :r.h5", "-log_view :r.h5", "performance log"},
    {"-log_view", "-log_view", "performance log"},
    {"-LOG_VIEW", "-LOG_VIEW", "performance log"},  // PETSc's names ignore case
    {"-Ksp_View ascii:x", "-Ksp_View ascii:x", "write the file x"},
    {"--log_view", "--log_view", "performance log"},
    {"-log_trace out.txt", "-log_trace out.txt", "performance log"},
    {"-history notes.txt", "-history notes.txt", "history file"},
    {"-citations refs.bib", "-citations refs.bib", "citations"},
    {"-malloc_dump leaks.txt", "-malloc_dump leaks.txt", "debugging option"},
    {"-malloc_debug", "-malloc_debug", "debugging option"},
    {"-info info.txt", "-info info.txt", "internal messages"},
    {"-pc_mg_dump_binary", "-pc_mg_dump_binary", "write or read a file"},
    {"-mat_mumps_icntl_1 7", "-mat_mumps_icntl_1 7", "output streams"},
    {"-mat_mumps_icntl_22 1", "-mat_mumps_icntl_22 1", "out-of-core"},
    {"-ksp_monitor_lg_residualnorm", "-ksp_monitor_lg_residualnorm", "draws in a window"},
    // Files read, help, other processes' business.
    {"-options_file /dev/zero", "-options_file /dev/zero", "reads PETSc options from a file"},
    {"-options_file_yaml o.yaml", "-options_file_yaml o.yaml", "reads PETSc options from a file"},
    {"-options_left", "-options_left", "prints the options database"},
    {"-prefix_push ksp_ -view", "-prefix_push ksp_", "renames the options"},
    {"-help", "-help", "print its help"},
    {"-help intro", "-help intro", "print its help"},
    {"-h", "-h", "print its help"},
    {"-version", "-version", "version"},
    {"-pc_type python", "-pc_type python", "Python"},
    {"-dll_append libx.so", "-dll_append libx.so", "loads code"},
    {"-pc_hypre_boomeramg_print_statistics", "-pc_hypre_boomeramg_print_statistics", "print its own output"},
    {"-no_signal_handler", "-no_signal_handler", "set by igacontact"},
    {"-snes_type newtonls", "-snes_type newtonls", "not an option of the linear solver"},
    // Numbers PETSc takes without a check.
    {"-ksp_rtol nan", "-ksp_rtol nan", "finite number in [0, 1)"},
    {"-ksp_rtol -1", "-ksp_rtol -1", "finite number in [0, 1)"},
    {"-ksp_rtol 1", "-ksp_rtol 1", "finite number in [0, 1)"},
    {"-ksp_rtol abc", "-ksp_rtol abc", "finite number in [0, 1)"},
    {"-ksp_rtol", "-ksp_rtol", "finite number in [0, 1)"},
    {"-ksp_atol inf", "-ksp_atol inf", "finite number >= 0"},
    {"-ksp_divtol 0.5", "-ksp_divtol 0.5", "finite number >= 1"},
    {"-ksp_max_it 0", "-ksp_max_it 0", "integer in [1, 1000000]"},
    {"-ksp_max_it 1e9", "-ksp_max_it 1e9", "integer in [1, 1000000]"},
    {"-mg_levels_ksp_max_it -3", "-mg_levels_ksp_max_it -3", "integer in [1, 1000000]"},
    {"-ksp_gmres_restart 1000000000", "-ksp_gmres_restart 1000000000", "integer in [1, 1000]"},
    {"-mat_mumps_icntl_7 abc", "-mat_mumps_icntl_7 abc", "must be an integer"},
    {"-mat_mumps_icntl_7 99999999999", "-mat_mumps_icntl_7 99999999999", "must be an integer"},
    {"-mat_mumps_cntl_1 nan", "-mat_mumps_cntl_1 nan", "finite number"},
    // Words that are not options.
    {"ksp_rtol 1e-6", "ksp_rtol", "is not an option: options start with a dash"},
    {"-ksp_rtol 1e-6 1e-7", "1e-7", "has its value already"},
    {"-", "-", "is not an option"},
    {"-pc_type 'jacobi'", "'", "quote"},
    {"-pc_type \"jacobi\"", "\"", "quote"},
    {"-ksp.rtol 1e-6", "-ksp.rtol 1e-6", "not an option name"},
};

TEST(PetscOptions, AnOptionThatWritesReadsPrintsOrTakesAnAbsurdNumberIsRefused)
{
    for (const Refused& r : refused) {
        const PetscOptionsCheck check = check_petsc_options(r.text, PetscOptionsSource::deck);
        ASSERT_FALSE(check.ok()) << "'" << r.text << "' passed";
        EXPECT_EQ(check.refused, r.refused) << r.text << ": " << check.message();
        EXPECT_NE(check.reason.find(r.reason), std::string::npos) << r.text << ": " << check.message();
        EXPECT_EQ(check.message(), check.refused + ": " + check.reason);
    }
}

TEST(PetscOptions, TheEnvironmentIsSplitAtSpacesOnly)
{
    // PETSc splits PETSC_OPTIONS itself, at spaces: a tab would join two options into
    // one name it never reads, so the environment refuses what the deck accepts.
    EXPECT_TRUE(check_petsc_options("-pc_type\tgamg", PetscOptionsSource::deck).ok());
    const PetscOptionsCheck check = check_petsc_options("-pc_type\tgamg", PetscOptionsSource::environment);
    ASSERT_FALSE(check.ok());
    EXPECT_NE(check.reason.find("spaces only"), std::string::npos) << check.message();
    EXPECT_TRUE(check_petsc_options("-pc_type gamg -ksp_monitor", PetscOptionsSource::environment).ok());
}

TEST(PetscOptions, TheFirstRefusedOptionIsNamedAndThoseBeforeItKept)
{
    const PetscOptionsCheck check =
        check_petsc_options("-pc_type gamg -ksp_view ascii:base.yaml -log_view", PetscOptionsSource::deck);
    EXPECT_EQ(check.refused, "-ksp_view ascii:base.yaml");
    ASSERT_EQ(check.options.size(), 1u);
    EXPECT_EQ(check.options[0].text(), "-pc_type gamg");
}

TEST(PetscOptions, TheEnvironmentIsCheckedWithItsVariableNamed)
{
    ASSERT_EQ(setenv("PETSC_OPTIONS", "-ksp_monitor -pc_type jacobi", 1), 0);
    unsetenv("PETSC_OPTIONS_YAML");
    EXPECT_EQ(checked_environment_options().size(), 2u);
    ASSERT_EQ(setenv("PETSC_OPTIONS", "-options_file /dev/zero", 1), 0);
    try {
        checked_environment_options();
        ADD_FAILURE() << "-options_file passed";
    } catch (const PetscOptionsError& e) {
        EXPECT_EQ(e.source(), PetscOptionsSource::environment);
        EXPECT_EQ(e.environment_issue().format().rfind("environment: error: PETSC_OPTIONS = -options_file /dev/zero: "
                                                       "-options_file /dev/zero: reads PETSc options from a file",
                                                       0),
                  0u)
            << e.environment_issue().format();
    }
    unsetenv("PETSC_OPTIONS");
    // PETSc reads PETSC_OPTIONS_YAML after PETSC_OPTIONS: refused whatever it holds.
    ASSERT_EQ(setenv("PETSC_OPTIONS_YAML", "ksp_view: ascii:deck.yaml", 1), 0);
    try {
        checked_environment_options();
        ADD_FAILURE() << "PETSC_OPTIONS_YAML passed";
    } catch (const PetscOptionsError& e) {
        EXPECT_EQ(e.variable(), "PETSC_OPTIONS_YAML");
    }
    unsetenv("PETSC_OPTIONS_YAML");
    EXPECT_TRUE(checked_environment_options().empty());
}

}  // namespace
}  // namespace iga
