#include "bim/plan.hpp"

namespace isg::bim {

namespace {

template <typename T>
const T* findById(const std::vector<T>& items, const std::string& id) {
  for (const auto& item : items) {
    if (item.id == id) return &item;
  }
  return nullptr;
}

template <typename Finder>
const Level* findLevelWith(const std::vector<Level>& levels, Finder finder) {
  for (const auto& level : levels) {
    if (finder(level) != nullptr) return &level;
  }
  return nullptr;
}

}  // namespace

bool isIfcGlobalId(std::string_view text) {
  constexpr std::string_view kAlphabet =
      "0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz_$";
  return text.size() == 22 && text[0] >= '0' && text[0] <= '3' &&
         text.find_first_not_of(kAlphabet) == std::string_view::npos;
}

const Wall* Level::findWall(const std::string& wall_id) const { return findById(walls, wall_id); }
const Door* Level::findDoor(const std::string& door_id) const { return findById(doors, door_id); }
const Window* Level::findWindow(const std::string& window_id) const {
  return findById(windows, window_id);
}
const Room* Level::findRoom(const std::string& room_id) const { return findById(rooms, room_id); }
const Stair* Level::findStair(const std::string& stair_id) const {
  return findById(stairs, stair_id);
}

const Column* Level::findColumn(const std::string& column_id) const {
  return findById(columns, column_id);
}

const Level* Plan::findLevel(const std::string& level_id) const {
  return findById(levels, level_id);
}

const Level* Plan::levelOfWall(const std::string& wall_id) const {
  return findLevelWith(levels, [&](const Level& l) { return l.findWall(wall_id); });
}

const Level* Plan::levelOfDoor(const std::string& door_id) const {
  return findLevelWith(levels, [&](const Level& l) { return l.findDoor(door_id); });
}

const Level* Plan::levelOfRoom(const std::string& room_id) const {
  return findLevelWith(levels, [&](const Level& l) { return l.findRoom(room_id); });
}

}  // namespace isg::bim
