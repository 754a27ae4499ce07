"""Graph routines shared by the layers (fabtiles/core/graph.py) against plain references."""

import networkx as nx
import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis_scale import examples

from fabtiles.core.graph import chain_ranks, components


@settings(max_examples=examples(50), deadline=None)
@given(st.integers(1, 60), st.lists(st.tuples(st.integers(0, 59), st.integers(0, 59)), max_size=80))
def test_components_as_networkx(n, edges):
    edges = [(a % n, b % n) for a, b in edges]
    g = nx.Graph()
    g.add_nodes_from(range(n))
    g.add_edges_from(edges)
    want = np.empty(n, np.int64)
    for comp in nx.connected_components(g):
        want[list(comp)] = min(comp)
    u = np.array([a for a, _ in edges], np.int64)
    v = np.array([b for _, b in edges], np.int64)
    assert components(n, u, v).tolist() == want.tolist()


@settings(max_examples=examples(50), deadline=None)
@given(st.lists(st.integers(1, 40), min_size=1, max_size=12), st.integers(0, 2**31 - 1))
def test_chain_ranks_walk_each_chain(lengths, seed):
    """Chains of random lengths laid out in a random order: heads and ranks as a walk finds them."""
    rng = np.random.default_rng(seed)
    n = sum(lengths)
    node = rng.permutation(n)
    pred = np.full(n, -1)
    want_head, want_rank = np.empty(n, np.int64), np.empty(n, np.int64)
    at = 0
    for length in lengths:
        chain = node[at : at + length]
        at += length
        pred[chain[1:]] = chain[:-1]
        want_head[chain] = chain[0]
        want_rank[chain] = np.arange(length)
    head, rank = chain_ranks(pred)
    assert head.tolist() == want_head.tolist() and rank.tolist() == want_rank.tolist()
