#include "fe/FiniteElementSpace.h"

namespace plate {

std::unique_ptr<FiniteElementSpace> makeSpace(ElementType type, const Mesh& mesh) {
    return type == ElementType::Fvs ? makeFvsSpace(mesh) : makeArgyrisSpace(mesh);
}

}  // namespace plate
