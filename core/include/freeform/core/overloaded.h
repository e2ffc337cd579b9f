// Overloaded{handler...}: one visitor from a handler per kind, for the
// std::visit of the geometry variants (Curve, CurveBasis, Surface) by the
// core and the server. A visit with one handler per kind fails to compile
// when a kind is added, until every dispatch decides what to do with it.
#ifndef FREEFORM_CORE_OVERLOADED_H_
#define FREEFORM_CORE_OVERLOADED_H_

namespace freeform {

template <typename... Handlers>
struct Overloaded : Handlers... {
  using Handlers::operator()...;
};
// Needed by clang 14, which does not deduce an aggregate's arguments.
template <typename... Handlers>
Overloaded(Handlers...) -> Overloaded<Handlers...>;

}  // namespace freeform

#endif  // FREEFORM_CORE_OVERLOADED_H_
