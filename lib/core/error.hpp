#pragma once
// The three kinds of error in igacontact, one mechanism each:
//  - bad input (the user's): throw DeckError, located as "file:line:col: error:
//    key.path = value: reason"; several may travel together in one DeckError;
//  - numerical failure (the run's fate): a returned status, never an exception;
//  - a bug (ours): IGA_ASSERT (debug builds, hot paths) / IGA_CHECK (always),
//    which throw iga::Error with the source location;
//  - the file system refusing a write (full disk, quota, read-only, I/O error):
//    StorageError, the run's fate, not a bug.
// Only app/ prints messages and chooses exit codes.

#include <stdexcept>
#include <string>
#include <vector>

namespace iga {

/// Internal error: a violated precondition or invariant (exit code 3).
class Error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// A write the file system refused (errno ENOSPC, EDQUOT, EFBIG, EROFS or EIO): the
/// run failed (exit code 1), nothing is wrong with the program or the deck.
class StorageError : public Error {
public:
    using Error::Error;
};

/// Where a deck value came from. line/column are 1-based; 0 means unknown
/// (e.g. a value given with --set, whose file is "<command line>").
struct SourceLocation {
    std::string file;
    int line = 0;
    int column = 0;
};

/// One located problem in a deck.
struct DeckIssue {
    SourceLocation where;
    std::string path;    ///< key path in --set syntax, e.g. "materials.steel.nu"
    std::string value;   ///< the offending value as written, may be empty
    std::string reason;  ///< what was expected

    /// "file:line:col: error: path = value: reason" (parts that are unknown are left out).
    std::string format() const;
};

/// Bad input (exit code 2). Holds one or more issues; what() lists them, one per line.
class DeckError : public std::runtime_error {
public:
    explicit DeckError(std::vector<DeckIssue> issues);
    explicit DeckError(DeckIssue issue);
    const std::vector<DeckIssue>& issues() const { return issues_; }

private:
    std::vector<DeckIssue> issues_;
};

[[noreturn]] void raise_internal_error(const char* condition, const std::string& message, const char* file,
                                       int line);

}  // namespace iga

/// Always-on check at module boundaries: throws iga::Error naming the condition and location.
#define IGA_CHECK(cond, msg)                                                        \
    do {                                                                            \
        if (!(cond))                                                                \
            ::iga::raise_internal_error(#cond, (msg), __FILE__, __LINE__);          \
    } while (false)

/// Debug-only check for hot paths.
#ifdef NDEBUG
#define IGA_ASSERT(cond, msg) \
    do {                      \
    } while (false)
#else
#define IGA_ASSERT(cond, msg) IGA_CHECK(cond, msg)
#endif
