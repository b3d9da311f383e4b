#pragma once
// The token of vsi serve: where it must be given, and the check of a request's
// "Authorization: Bearer <token>" header.
#include <string>
#include <string_view>

namespace railvsi::scheduler {

// 127.0.0.0/8, ::1 and localhost: addresses only this host reaches.
bool is_loopback_address(std::string_view address);

// Whether `authorization` (the header's value, empty when absent) carries
// `token`. Compares every byte whatever the first difference, so that the
// time taken tells nothing of the token.
bool bearer_matches(std::string_view authorization, std::string_view token);

}  // namespace railvsi::scheduler
