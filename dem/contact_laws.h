// The contact laws a Material can select, listed once: each normal law names
// its ContactLaw value (Law::kContactLaw), and every law runs plain or
// decorated with rolling resistance. The engine's law (AnyContactLaw), the
// contact durations, the stiffness number, the adaptive time step and the κ
// column's description all dispatch through this list, so that a new law is
// its header, its ContactLaw value and keys (material.h/.cc) and one entry in
// ContactLaws below.
#pragma once

#include <iterator>
#include <string>
#include <variant>

#include "common/error.h"
#include "dem/hertz_mindlin.h"
#include "dem/linear_cundall_strack.h"
#include "dem/material.h"
#include "dem/rolling_resistance.h"

namespace granasym::dem {

template <class... Laws>
struct ContactLawList {
  // Every law plain and with rolling resistance (in this order).
  using Variant = std::variant<Laws..., RollingResistance<Laws>...>;
  static constexpr size_t kSize = sizeof...(Laws);
};

// The normal laws.
using ContactLaws = ContactLawList<LinearCundallStrack, HertzMindlin>;
static_assert(ContactLaws::kSize == std::size(EnumNames<ContactLaw>::kEntries),
              "every ContactLaw value needs its law in ContactLaws");

// The law of an Engine: any of the list, plain or with rolling resistance.
using AnyContactLaw = ContactLaws::Variant;

// A law type as a value, handed to the visitors of VisitContactLaw.
template <class Law>
struct LawType {
  using type = Law;
};

namespace internal {
template <class Visitor, class Law, class... Rest>
decltype(auto) VisitContactLaw(const Material& material, Visitor& visit,
                               ContactLawList<Law, Rest...>) {
  if (material.contact_law == Law::kContactLaw) {
    if (material.has_rolling_resistance()) return visit(LawType<RollingResistance<Law>>{});
    return visit(LawType<Law>{});
  }
  if constexpr (sizeof...(Rest) > 0) {
    return VisitContactLaw(material, visit, ContactLawList<Rest...>{});
  } else {
    GRANASYM_CHECK(false) << "unknown contact law";
    return visit(LawType<Law>{});
  }
}
}  // namespace internal

// visit(LawType<L>{}) for the material's law L: its normal law, wrapped in
// RollingResistance where it has rolling resistance. Every call of `visit`
// must return the same type.
template <class Visitor>
decltype(auto) VisitContactLaw(const Material& material, Visitor&& visit) {
  return internal::VisitContactLaw(material, visit, ContactLaws{});
}

// The stiffness numbers' definitions, law by law ("E/(2p) for the linear
// law, (E*/p)^(2/3) for Hertz-Mindlin"): the κ column's description.
template <class... Laws>
std::string StiffnessNumberDescriptions(ContactLawList<Laws...>) {
  std::string text;
  ((text += (text.empty() ? "" : ", ") + Laws::StiffnessNumberDescription()), ...);
  return text;
}
inline std::string StiffnessNumberDescriptions() {
  return StiffnessNumberDescriptions(ContactLaws{});
}

}  // namespace granasym::dem
