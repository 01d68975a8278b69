// The check every bad-input test makes: a call throws penumbra::Error of the
// expected category, naming the operation, with a message that holds the
// expected fragment (the parameter's name, the file, the value).
#pragma once

#include <gtest/gtest.h>

#include <initializer_list>
#include <optional>
#include <string>

#include "penumbra/error.h"

namespace penumbra::testing {

// One row of a table of bad inputs: what is passed (options, a value) and
// the text its error must hold (the parameter's or the option's name).
struct BadInput {
    std::string input;
    std::string needle;
};

// Runs `call`, expecting Error(`category`) from `operation` (any, when empty)
// whose message holds every one of `needles` (say the file and what is wrong).
template <class Call>
void expect_error(Call&& call, ErrorCategory category, const std::string& operation,
                  std::initializer_list<std::string> needles)
{
    try {
        call();
        ADD_FAILURE() << "no error; expected one mentioning \"" << *needles.begin() << "\"";
    } catch (const Error& e) {
        EXPECT_EQ(e.category(), category) << e.what();
        if (!operation.empty()) {
            EXPECT_EQ(e.operation(), operation) << e.what();
        }
        for (const std::string& needle : needles)
            EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << "\"" << e.what() << "\" lacks " << needle;
    }
}

template <class Call>
void expect_error(Call&& call, ErrorCategory category, const std::string& operation, const std::string& needle)
{
    expect_error(call, category, operation, {needle});
}

// The same, from any operation.
template <class Call>
void expect_error(Call&& call, ErrorCategory category, const std::string& needle)
{
    expect_error(call, category, std::string(), {needle});
}

template <class Call>
void expect_error(Call&& call, ErrorCategory category, std::initializer_list<std::string> needles)
{
    expect_error(call, category, std::string(), needles);
}

// Runs `action` and returns the penumbra::Error it threw, if any. Any other
// exception escapes and fails the test, which is the point: none may leak out.
template <class Action>
std::optional<Error> error_from(Action&& action)
{
    try {
        action();
    } catch (const Error& error) {
        return error;
    }
    return std::nullopt;
}

inline bool mentions(const Error& error, const std::string& text)
{
    return std::string(error.what()).find(text) != std::string::npos;
}

}  // namespace penumbra::testing
