// PETSc's options on the built executable (issue 32; the refusals are cases of
// verification/bad_input, the tokenizer's rules tests/core/petsc_options_test.cpp):
// PETSc reads no options file of the working folder, what it prints goes to standard
// error so that standard output stays the run's summary, and an option no solver read
// is named in the run's warnings. Runs the bad-input suite's base deck (~0.2 s).

#include "cli_support.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace iga::test {
namespace {

namespace fs = std::filesystem;

/// A scratch folder holding the bad-input suite's base deck as base.yaml.
fs::path folder_with_deck(const std::string& name)
{
    const fs::path dir = fs::path(IGA_BINARY_DIR) / "test_scratch" / "app" / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    fs::copy_file(fs::path(IGA_SOURCE_DIR) / "verification" / "bad_input" / "base.yaml", dir / "base.yaml");
    return dir;
}

TEST(PetscOptions, NoOptionsFileOfTheWorkingFolderIsRead)
{
#ifndef IGACONTACT_HAVE_PETSC
    GTEST_SKIP() << "built without PETSc";
#endif
    // PETSc reads .petscrc and petscrc in the working folder unless told not to: these
    // would write over the deck and write a log, unchecked.
    const fs::path dir = folder_with_deck("petscrc");
    std::ofstream(dir / ".petscrc") << "-ksp_view ascii:base.yaml\n";
    std::ofstream(dir / "petscrc") << "-log_view :petsc_log.txt\n";
    const std::string deck = read_text(dir / "base.yaml");
    const std::string command = "cd " + shell_quote(dir.string()) + " && " + shell_quote(cli_path()) +
                                " base.yaml -q -o out.h5 --set solver.backend=petsc";
    const int status = std::system((command + " > out.txt 2> err.txt < /dev/null").c_str());
    ASSERT_TRUE(WIFEXITED(status)) << command;
    EXPECT_EQ(WEXITSTATUS(status), 0) << read_text(dir / "err.txt");
    EXPECT_EQ(read_text(dir / "base.yaml"), deck) << "the deck was written over";
    EXPECT_FALSE(fs::exists(dir / "petsc_log.txt"));
    EXPECT_TRUE(fs::exists(dir / "out.h5"));
}

TEST(PetscOptions, WhatPetscPrintsGoesToStandardErrorAndTheSummaryStaysOneLine)
{
#ifndef IGACONTACT_HAVE_PETSC
    GTEST_SKIP() << "built without PETSc";
#endif
    const fs::path dir = folder_with_deck("petsc_monitor");
    const CliResult r = run_cli(shell_quote((dir / "base.yaml").string()) + " -q --summary json -o " +
                                    shell_quote((dir / "out.h5").string()) +
                                    " --set solver.type=iterative --set solver.options=-ksp_monitor",
                                dir);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    ASSERT_FALSE(r.out.empty());
    EXPECT_EQ(r.out.find('\n'), r.out.size() - 1) << "one line on standard output:\n" << r.out;
    EXPECT_EQ(r.out.front(), '{') << r.out;
    EXPECT_NE(r.err.find("KSP Residual norm"), std::string::npos) << "the monitor, on standard error:\n" << r.err;
}

TEST(PetscOptions, AnOptionNoSolverReadIsNamedInTheWarnings)
{
#ifndef IGACONTACT_HAVE_PETSC
    GTEST_SKIP() << "built without PETSc";
#endif
    const fs::path dir = folder_with_deck("petsc_unread");
    const CliResult r = run_cli(shell_quote((dir / "base.yaml").string()) + " -q -o " +
                                    shell_quote((dir / "out.h5").string()) +
                                    " --set solver.type=iterative --set 'solver.options=-ksp_rtoll 1e-9'",
                                dir);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("warning: PETSc options cg + gamg did not read: -ksp_rtoll (solver.options)"),
              std::string::npos)
        << r.err;
}

}  // namespace
}  // namespace iga::test
