#pragma once
// Stage 3 of 6 (part 1): subdivision schemes as data. A scheme is its arity,
// one rule (a weight list and where it starts) per child position, and a named
// boundary rule; one generic refiner (refine.h) applies any of them. Masks and
// their derivations: docs/schemes.md (from the source papers). A scheme spec
// from a scene or the command line becomes a Scheme in one place only:
// resolveScheme (subdiv/resolve.h).
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/diagnostics.h"

namespace relief::subdiv {

/// New point of child position r:  P'_{m*i + r} = sum_j weights[j] * P_{i + offset + j}.
struct Rule {
    int offset;
    std::vector<double> weights;  ///< sum to 1
};

/// How the points beyond the net's edge (the papers' ghost points) are made.
enum class Boundary {
    /// P_{-j} = 2 P_0 - P_j (and the mirror at the far end), regenerated at
    /// every level. For symmetric schemes the edge points stay fixed and linear
    /// data (a regular x, y lattice) are reproduced exactly.
    PointReflection,
};

/// Largest arity a Scheme has: binary and ternary schemes.
inline constexpr int kMaxArity = 3;

struct Scheme {
    std::string name;
    int arity = 2;            ///< 2 (binary) or 3 (ternary)
    std::vector<Rule> rules;  ///< rules[r] for child position r = 0 .. arity-1
    Boundary boundary = Boundary::PointReflection;

    /// Ghost points needed before the first and after the last point.
    int ghostsBefore() const;
    int ghostsAfter() const;
    /// Number of points after one step on an open curve of n points: m(n-1)+1.
    long long refinedCount(long long n) const { return arity * (n - 1) + 1; }
};

/// A named, parameterised family of schemes (the registry's entries).
struct ParamSpec {
    std::string name;
    double defaultValue;
    double lo, hi;  ///< valid range, inclusive
    std::string meaning;
};

using SchemeParams = std::map<std::string, double>;

/// A row of the scheme table. Adding a scheme is adding a row here (and its
/// tests); docs/schemes.md says how.
struct SchemeFamily {
    std::string name;
    std::string description;
    std::string source;  ///< where it comes from, e.g. "paper 001"
    std::vector<ParamSpec> params;
    std::function<Scheme(const SchemeParams&)> build;
    /// Warnings for parameter values that work but surprise (e.g. asymmetry).
    std::function<std::vector<std::string>(const SchemeParams&)> caveats;
    /// The source paper's own (sufficient) conditions for these parameters,
    /// which hold and which fail, as notes for `relief check`; `smoothness` is
    /// the certified class (-1: convergence not proven), for notes that
    /// compare the paper's claim with the certificate.
    std::function<std::vector<std::string>(const SchemeParams&, int smoothness)> paperConditions;
};

const std::vector<SchemeFamily>& schemeFamilies();
const SchemeFamily* findSchemeFamily(const std::string& name);


// The families, also callable directly (tests, benchmarks).
Scheme dlgFourPoint(double w);                                             // w = 1/16: classic
Scheme fourPoint4p(double lambda, double mu, double nu, double omega);     // paper 001
Scheme binary3p(double lambda, double mu, double omega);                   // paper 000
Scheme ternaryBlend(double alpha, double beta, double gamma);               // paper 004
Scheme ternaryFourPoint(double theta);                                     // paper 004
Scheme ternaryBSpline(double eta);                                         // paper 004

/// A named special case: a family and fixed parameters (e.g. "hassan" =
/// ternary-blend with beta = 1/18 + mu/6, gamma = 1/18 - mu/6). A preset may
/// take parameters of its own (Hassan's mu).
struct Preset {
    std::string name;
    std::string description;
    std::string family;
    std::vector<ParamSpec> params;  ///< the preset's own parameters, if any
    std::function<std::map<std::string, double>(const std::map<std::string, double>&)> familyParams;
};
const std::vector<Preset>& presets();
const Preset* findPreset(const std::string& name);

/// A user's own scheme from its mask (symbol coefficients a_k, k = first, first+1, ...):
/// P'_{m i + r} = sum_l a_{m i + r - m l} P_l. Reports masks whose child
/// positions do not each sum to 1 (then the scheme cannot converge).
std::optional<Scheme> schemeFromMask(int arity, int first, const std::vector<double>& mask,
                                     const SourceLoc& loc, Diagnostics& diags);

/// The scheme table as Markdown (families with their parameters, then
/// presets): `relief check --list`, and the table in docs/schemes.md.
std::string schemeTableMarkdown();

}  // namespace relief::subdiv
