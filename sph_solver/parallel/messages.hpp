#pragma once
// Point-to-point messages of the domain decomposition and the halo: byte buffers
// posted as non-blocking sends and receives, then completed together.
//
// Values travel as their "wire" form: a trivially copyable type whose bytes are
// the value. A trivially copyable type is its own wire form; a fixed-size Eigen
// matrix (Eigen::Vector3d is not trivially copyable) travels as an array of its
// coefficients. Both ends run the same executable, so the bytes need no conversion.
//
// Tags: messages of one kind between two ranks are matched in the order they were
// posted (MPI's non-overtaking rule), so one fixed tag per kind suffices; the tags
// below must not be used by other messages on the same communicator.
#include <Eigen/Core>
#include <mpi.h>

#include <array>
#include <cstddef>
#include <span>
#include <type_traits>
#include <vector>

namespace tankfsi::sph {

namespace message_tag {
inline constexpr int halo_count = 7300;
inline constexpr int halo_exchange = 7301;
inline constexpr int halo_accumulate = 7302;
inline constexpr int migration = 7303;
}  // namespace message_tag

/// Wire<T>::type is what a T travels as; to_wire / from_wire convert.
template <class T>
struct Wire {
  using type = T;
  static type to_wire(const T& value) { return value; }
  static T from_wire(const type& wire) { return wire; }
};

template <class Scalar, int Rows, int Cols, int Options, int MaxRows, int MaxCols>
  requires(Rows > 0 && Cols > 0)
struct Wire<Eigen::Matrix<Scalar, Rows, Cols, Options, MaxRows, MaxCols>> {
  using Value = Eigen::Matrix<Scalar, Rows, Cols, Options, MaxRows, MaxCols>;
  using type = std::array<Scalar, static_cast<std::size_t>(Rows * Cols)>;
  static type to_wire(const Value& value) {
    type wire;
    Eigen::Map<Value>(wire.data()) = value;
    return wire;
  }
  static Value from_wire(const type& wire) { return Eigen::Map<const Value>(wire.data()); }
};

template <class T>
using WireType = typename Wire<T>::type;

/// Types a halo can exchange: those whose wire form is trivially copyable.
template <class T>
concept HaloValue = std::is_trivially_copyable_v<WireType<T>> && std::is_default_constructible_v<T>;

/// Posts a receive of buffer.size() bytes from `source` and appends its request.
/// Throws std::length_error if the message exceeds 2^31 - 1 bytes.
void post_receive(std::span<std::byte> buffer, int source, int tag, MPI_Comm comm, std::vector<MPI_Request>& requests);

/// Posts a send of the bytes of `buffer` to `destination` and appends its request.
/// The buffer must stay alive and unchanged until wait_all(). Throws like post_receive.
void post_send(std::span<const std::byte> buffer, int destination, int tag, MPI_Comm comm,
               std::vector<MPI_Request>& requests);

/// Completes every request, then empties the list.
void wait_all(std::vector<MPI_Request>& requests);

}  // namespace tankfsi::sph
