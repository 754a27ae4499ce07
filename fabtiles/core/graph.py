"""Graph routines in numpy shared by the layers: connected components, ranks along chains.

Both are pointer jumping: a few rounds of whole-array gathers instead of a Python
loop over the nodes (the mesh check counts the bodies of 480,000 triangles; the
weave walks 60,000 pieces along their strands).
"""

from __future__ import annotations

import numpy as np


def components(n: int, u, v) -> np.ndarray:
    """Component label of each of ``n`` nodes joined by edges ``u[i] - v[i]``: the smallest node in it.

    Each round hooks the larger root of every edge onto the smaller one and jumps
    pointers to the roots; edges inside one component drop out. Five or six rounds
    on the sheets' meshes (scipy's ``connected_components`` is as fast, but importing
    scipy would slow every command's start).

    >>> components(6, np.array([0, 1, 4]), np.array([1, 2, 3])).tolist()
    [0, 0, 0, 3, 3, 5]
    """
    parent = np.arange(n)
    u, v = np.asarray(u), np.asarray(v)
    while len(u):
        pu, pv = parent[u], parent[v]
        apart = pu != pv
        u, v, pu, pv = u[apart], v[apart], pu[apart], pv[apart]
        if not len(u):
            break
        np.minimum.at(parent, np.maximum(pu, pv), np.minimum(pu, pv))
        while True:
            nxt = parent[parent]
            if np.array_equal(nxt, parent):
                break
            parent = nxt
    return parent


def chain_ranks(pred) -> tuple[np.ndarray, np.ndarray]:
    """``(head, rank)`` of each node of chains given by predecessors (``-1``: a chain's head).

    ``rank`` counts the nodes before a node on its chain (0 at the head). The
    chains must hold no cycle. Wyllie's pointer jumping: log2 of the longest chain
    rounds.

    >>> head, rank = chain_ranks(np.array([-1, 0, 1, -1, 3]))
    >>> head.tolist(), rank.tolist()
    ([0, 0, 0, 3, 3], [0, 1, 2, 0, 1])
    """
    pred = np.asarray(pred)
    node = np.arange(len(pred))
    jump = np.where(pred >= 0, pred, node)
    rank = (pred >= 0).astype(np.int64)
    while True:
        nxt = jump[jump]
        if np.array_equal(nxt, jump):
            return jump, rank
        rank = rank + rank[jump]
        jump = nxt
