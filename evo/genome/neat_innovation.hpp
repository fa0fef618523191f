#pragma once
// NEAT's historical markings (Stanley & Miikkulainen 2002, section 3.2): every new connection gene
// gets an innovation number and every node made by splitting a connection gets a node id, both
// from counters kept per run. Within one generation the same structural mutation gets the same
// numbers, so genomes that made it independently still align in crossover and speciation: a new
// connection is identified by its end nodes' ids, a split by the connection it splits. The table
// of this generation's mutations is forgotten at the next generation (as in the paper); only the
// counters carry over, so a checkpoint stores just the two counters.
#include <cstdint>
#include <map>
#include <utility>

namespace bhm::evo {

class InnovationTable {
  public:
    //! next_node_id: the first id a split may hand out (above every input and output id).
    InnovationTable(std::int64_t next_innovation, std::int64_t next_node_id)
        : next_innovation_(next_innovation), next_node_id_(next_node_id) {}

    //! The innovation number of connection from_id -> to_id: this generation's if it was made
    //! already, else a new one.
    std::int64_t connection(std::int64_t from_id, std::int64_t to_id);

    struct Split {
        std::int64_t node_id = 0;         //!< the new hidden node
        std::int64_t in_innovation = 0;   //!< from -> node
        std::int64_t out_innovation = 0;  //!< node -> to
    };
    //! The node and two connections that replace connection `innovation` (from_id -> to_id) when
    //! it is split: the same for every genome that splits it this generation.
    Split split(std::int64_t innovation, std::int64_t from_id, std::int64_t to_id);

    //! Forgets this generation's mutations; the counters go on.
    void new_generation();

    std::int64_t next_innovation() const { return next_innovation_; }
    std::int64_t next_node_id() const { return next_node_id_; }

  private:
    std::int64_t next_innovation_ = 0;
    std::int64_t next_node_id_ = 0;
    std::map<std::pair<std::int64_t, std::int64_t>, std::int64_t> connections_;
    std::map<std::int64_t, Split> splits_;
};

}  // namespace bhm::evo
