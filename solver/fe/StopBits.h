#pragma once
// Which obstacles' stops cover a contact row (docs/theory.md §25): the bits a clamped plate's contact
// rows carry (ClampedPlate::contactStops) and the obstacles read (plate/Obstacles.h).

namespace plate {

enum StopBits : unsigned char { kUnderLower = 1, kUnderUpper = 2, kUnderBoth = 3 };

}  // namespace plate
