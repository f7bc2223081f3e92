#pragma once
// Helpers for the whole-solver tests: run a deck in-process (io::read_deck with
// --set overrides, then analysis::run) into a scratch folder of the build tree,
// and read the results file back through the documented layout only
// (docs/results.md), never through solver internals.
//
// Scratch folders: ${IGA_BINARY_DIR}/test_scratch/analysis/<name>, emptied on
// creation; each test uses its own name, so ctest -j cannot make tests collide.
// Shapes follow results.md: displacement n_cp x d, control_points n_cp x (d+1),
// convergence n x 4 (increment, iteration, relative residual, load factor).

#include "analysis/run.hpp"
#include "core/run_context.hpp"
#include "core/types.hpp"
#include "io/deck_reader.hpp"
#include "io/h5_file.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

namespace iga::test {

inline std::string source_path(const std::string& relative)
{
    return std::string(IGA_SOURCE_DIR) + "/" + relative;
}

inline std::string app_path()
{
    return std::string(IGA_BINARY_DIR) + "/bin/igacontact";
}

/// An empty folder for one test's files.
inline std::filesystem::path scratch_dir(const std::string& name)
{
    const std::filesystem::path dir = std::filesystem::path(IGA_BINARY_DIR) / "test_scratch" / "analysis" / name;
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

/// Reads `deck_path` with the overrides, writes the results to `results_file`,
/// runs quietly and returns the outcome (the file is complete when it returns).
inline analysis::RunOutcome run_deck(const std::string& deck_path, const std::vector<std::string>& overrides,
                                     const std::filesystem::path& results_file)
{
    io::Deck deck = io::read_deck(deck_path, overrides);
    deck.output.file = results_file.string();
    RunContext context(nullptr, Verbosity::quiet);
    return analysis::run(deck, analysis::RunOptions{}, context);
}

/// Read access to one results file.
class Results {
public:
    explicit Results(const std::filesystem::path& path) : file_(io::h5::open_file(path.string())) {}

    hid_t id() const { return file_.id(); }
    bool exists(const std::string& path) const { return io::h5::exists(file_.id(), path); }

    /// A real dataset as a matrix (1-D datasets become one column).
    RowMatrix matrix(const std::string& path) const
    {
        const io::h5::Array a = io::h5::read_dataset(file_.id(), path);
        EXPECT_EQ(a.type, io::h5::Array::Type::real) << path << " is " << a.type_description;
        const Index rows = a.dims.empty() ? 1 : static_cast<Index>(a.dims[0]);
        const Index cols = a.dims.size() < 2 ? 1 : static_cast<Index>(a.dims[1]);
        RowMatrix m(rows, cols);
        for (Index k = 0; k < rows * cols && k < static_cast<Index>(a.reals.size()); ++k)
            m(k / cols, k % cols) = a.reals[static_cast<std::size_t>(k)];
        return m;
    }

    std::vector<double> reals(const std::string& path) const
    {
        const io::h5::Array a = io::h5::read_dataset(file_.id(), path);
        if (a.type == io::h5::Array::Type::integer)
            return std::vector<double>(a.integers.begin(), a.integers.end());
        return a.reals;
    }

    /// A numeric attribute of the object at `object_path` ("/" for the root).
    double number(const std::string& object_path, const std::string& name) const
    {
        const io::h5::Handle object = io::h5::open_object(file_.id(), object_path);
        const io::h5::Array a = io::h5::read_attribute(object.id(), name);
        if (a.type == io::h5::Array::Type::integer && !a.integers.empty())
            return static_cast<double>(a.integers.front());
        if (a.type == io::h5::Array::Type::real && !a.reals.empty())
            return a.reals.front();
        ADD_FAILURE() << object_path << "@" << name << " is not a number (" << a.type_description << ")";
        return std::nan("");
    }

    std::string text(const std::string& object_path, const std::string& name) const
    {
        const io::h5::Handle object = io::h5::open_object(file_.id(), object_path);
        const io::h5::Array a = io::h5::read_attribute(object.id(), name);
        if (a.type != io::h5::Array::Type::string || a.strings.empty()) {
            ADD_FAILURE() << object_path << "@" << name << " is not a string (" << a.type_description << ")";
            return {};
        }
        return a.strings.front();
    }

    /// The groups under /steps, in increment order ("0001", "0002", ...).
    std::vector<std::string> steps() const
    {
        if (!exists("steps"))
            return {};
        const io::h5::Handle group = io::h5::open_object(file_.id(), "steps");
        return io::h5::link_names(group.id());
    }

private:
    io::h5::Handle file_;
};

/// Newton's relative residuals e_0, e_1, ... of one increment, from /convergence.
inline std::vector<double> newton_residuals(const Results& results, int increment = 1)
{
    const RowMatrix table = results.matrix("convergence");
    EXPECT_EQ(table.cols(), 4);
    std::vector<double> e;
    for (Index k = 0; k < table.rows(); ++k)
        if (table(k, 0) == static_cast<double>(increment))
            e.push_back(table(k, 2));
    return e;
}

/// The last Newton step e_k -> e_{k+1} that ends above `roundoff_floor` (where an
/// order can still be read): k, or e.size() when there is none.
inline std::size_t last_step_above(const std::vector<double>& e, double roundoff_floor)
{
    std::size_t k = e.size();
    for (std::size_t i = 0; i + 1 < e.size(); ++i)
        if (e[i + 1] > roundoff_floor)
            k = i;
    return k;
}

/// Gauss-Legendre points and weights on [0, 1], computed here (Newton on P_n)
/// so that the error integrals do not use the quadrature under test.
inline void gauss_legendre_01(int n, std::vector<double>& points, std::vector<double>& weights)
{
    points.assign(static_cast<std::size_t>(n), 0.0);
    weights.assign(static_cast<std::size_t>(n), 0.0);
    const double pi = 3.14159265358979323846;
    for (int i = 0; i < n; ++i) {
        double x = std::cos(pi * (i + 0.75) / (n + 0.5));
        double dp = 1.0;
        for (int it = 0; it < 100; ++it) {
            double p0 = 1.0, p1 = x;
            for (int k = 2; k <= n; ++k) {
                const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
                p0 = p1;
                p1 = p2;
            }
            dp = n * (x * p1 - p0) / (x * x - 1.0);
            const double dx = p1 / dp;
            x -= dx;
            if (std::abs(dx) < 1e-16)
                break;
        }
        points[static_cast<std::size_t>(i)] = 0.5 * (1.0 - x);
        weights[static_cast<std::size_t>(i)] = 1.0 / ((1.0 - x * x) * dp * dp);
    }
}

}  // namespace iga::test
