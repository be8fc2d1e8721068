//! The arena: hash-consed nodes and interned symbol names.
//!
//! Every expression lives in a [`Pool`]. Building the same expression twice gives the same
//! [`Id`], so structural equality is `==` on ids and large derivations share their common
//! sub-expressions for free.

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, ToPrimitive, Zero};
use rustc_hash::FxHashMap;

use super::node::{Id, Node, Sym};

/// The hash of a node for the pool's index. A number is hashed by its numerator and
/// denominator in lowest terms, not by `BigRational`'s own hash, which expands the ratio as a
/// continued fraction (a big division per step) to stay equal for unreduced ratios: numbers
/// are hashed on every node built and again whenever the index grows. Equal numbers still
/// hash alike: a ratio that fits in machine integers is reduced here, and a larger one is
/// already reduced (every `BigRational` the crate makes is).
fn hash_node(node: &Node) -> u64 {
    use std::hash::{BuildHasher, Hash, Hasher};
    let Node::Num(v) = node else {
        return rustc_hash::FxBuildHasher.hash_one(node);
    };
    let mut h = rustc_hash::FxBuildHasher.build_hasher();
    match (v.numer().to_i64(), v.denom().to_i64()) {
        (Some(n), Some(d)) if d != 0 => {
            let g = gcd(n.unsigned_abs(), d.unsigned_abs()).max(1);
            let sign = n != 0 && (n < 0) != (d < 0);
            (sign, n.unsigned_abs() / g, d.unsigned_abs() / g).hash(&mut h);
        }
        _ => (v.numer(), v.denom()).hash(&mut h),
    }
    h.finish()
}

/// Greatest common divisor (Euclid's).
fn gcd(mut a: u64, mut b: u64) -> u64 {
    while b != 0 {
        (a, b) = (b, a % b);
    }
    a
}

/// Largest expression a differentiation may produce, and past which expansion is not done,
/// counted as a printed tree ([`Pool::tree_size`]). The 20-link pendulum's largest is about
/// 5,000; growth past this (a tower of powers, a product of many factors, differentiated)
/// is refused rather than printed by the megabyte.
pub const MAX_TREE_SIZE: usize = 25_000;

/// Most nodes one differentiation or one simplification may add to the pool: a bound on
/// its time and memory whatever the shape of the input.
pub const MAX_NEW_NODES: usize = 200_000;

/// A derivation that grew past [`MAX_TREE_SIZE`] or [`MAX_NEW_NODES`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
#[error("the derivation grows past {limit} nodes")]
pub struct TooLarge {
    /// The limit that was reached.
    pub limit: usize,
}

impl TooLarge {
    /// What to do about it, in one line.
    pub fn help(&self) -> String {
        "write the expression more simply: towers of powers and products of many factors grow fastest when differentiated".into()
    }
}

/// The name of the time symbol; always symbol 0 of a pool.
pub const TIME: &str = "t";

/// An arena of canonical expression nodes plus the symbol table they refer to.
#[derive(Clone, Debug)]
pub struct Pool {
    nodes: Vec<Node>,
    /// The size of each node written out as a tree (shared sub-expressions counted every
    /// time they occur, as a printer writes them), saturating: what printing would cost.
    sizes: Vec<u32>,
    /// Ids by the hash of their node; equality is checked against `nodes`, so nodes are
    /// stored once.
    index: hashbrown::HashTable<Id>,
    names: Vec<String>,
    sym_index: FxHashMap<String, Sym>,
    zero: Id,
    one: Id,
    minus_one: Id,
    /// Memo tables of the simplification passes (results depend only on the node, or for
    /// `roots` on the set of positive symbols stored alongside).
    pub(crate) caches: Caches,
    /// Memo of [`content`](Pool::content) by sum.
    pub(crate) contents: FxHashMap<Id, (num_rational::BigRational, Id)>,
    /// Memo of the sign test of sums (the printed-first term is costly to find).
    pub(crate) negative_sum: Memo,
    /// While a simplification runs: the pool size at which it gives up (see
    /// [`MAX_NEW_NODES`]).
    pub(crate) budget_end: Option<usize>,
}

/// A memo filled while printing (through `&Pool`). A mutex rather than a `RefCell` keeps the
/// pool `Sync`, so problems can be shared by reference between threads (a face grading a
/// class in parallel); it is never contended within one thread's use of a pool.
#[derive(Debug, Default)]
pub(crate) struct Memo(std::sync::Mutex<FxHashMap<Id, bool>>);

impl Memo {
    pub(crate) fn get(&self, id: Id) -> Option<bool> {
        self.0
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
            .get(&id)
            .copied()
    }

    pub(crate) fn insert(&self, id: Id, v: bool) {
        self.0
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
            .insert(id, v);
    }
}

impl Clone for Memo {
    fn clone(&self) -> Self {
        let inner = self
            .0
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
            .clone();
        Memo(std::sync::Mutex::new(inner))
    }
}

/// Per-node memo tables of the rewrite passes.
#[derive(Clone, Debug, Default)]
pub(crate) struct Caches {
    pub(crate) expand: FxHashMap<Id, Id>,
    pub(crate) trig: FxHashMap<Id, Id>,
    pub(crate) roots: FxHashMap<Id, Id>,
    pub(crate) roots_positive: Vec<Sym>,
}

impl Default for Pool {
    fn default() -> Self {
        Self::new()
    }
}

impl Pool {
    /// An empty pool holding only the constants 0, 1, −1 and the time symbol `t`.
    pub fn new() -> Self {
        let mut pool = Pool {
            nodes: Vec::new(),
            sizes: Vec::new(),
            index: hashbrown::HashTable::new(),
            names: Vec::new(),
            sym_index: FxHashMap::default(),
            zero: Id(0),
            one: Id(0),
            minus_one: Id(0),
            caches: Caches::default(),
            contents: FxHashMap::default(),
            negative_sum: Memo::default(),
            budget_end: None,
        };
        pool.zero = pool.intern(Node::Num(BigRational::zero()));
        pool.one = pool.intern(Node::Num(BigRational::one()));
        pool.minus_one = pool.intern(Node::Num(-BigRational::one()));
        pool.symbol(TIME);
        pool
    }

    /// Adds `node` unless an equal node exists; returns its id. Callers guarantee that the
    /// node is canonical (see `build.rs`).
    pub(crate) fn intern(&mut self, node: Node) -> Id {
        let hash = hash_node(&node);
        let nodes = &self.nodes;
        if let Some(&id) = self.index.find(hash, |&id| nodes[id.index()] == node) {
            return id;
        }
        let id = Id(u32::try_from(self.nodes.len()).expect("more than 2^32 expression nodes"));
        let size = self.tree_size_of(&node);
        self.sizes.push(size);
        self.nodes.push(node);
        let nodes = &self.nodes;
        self.index
            .insert_unique(hash, id, |&i| hash_node(&nodes[i.index()]));
        id
    }

    /// The node behind an id.
    pub fn node(&self, id: Id) -> &Node {
        &self.nodes[id.index()]
    }

    /// The number of nodes of `id` written out as a tree: every occurrence of a shared
    /// sub-expression counts, as it does when printed (saturates at `u32::MAX`).
    pub fn tree_size(&self, id: Id) -> usize {
        self.sizes[id.index()] as usize
    }

    /// The tree size of a node about to be interned: one plus its children's.
    fn tree_size_of(&self, node: &Node) -> u32 {
        let of = |c: &Id| self.sizes[c.index()];
        match node {
            Node::Num(_) | Node::Var(..) | Node::Pi => 1,
            Node::Add(c) | Node::Mul(c) => c.iter().fold(1u32, |acc, x| acc.saturating_add(of(x))),
            Node::Pow(b, e) => 1u32.saturating_add(of(b)).saturating_add(of(e)),
            Node::Func(_, a) => 1u32.saturating_add(of(a)),
        }
    }

    /// Whether the running simplification has added more nodes than it may.
    pub(crate) fn over_budget(&self) -> bool {
        self.budget_end.is_some_and(|end| self.len() > end)
    }

    /// Number of distinct nodes in the pool.
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// Whether the pool holds no nodes (never true: constants are pre-interned).
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// Interns a symbol name.
    pub fn symbol(&mut self, name: &str) -> Sym {
        if let Some(&s) = self.sym_index.get(name) {
            return s;
        }
        let s = Sym(u32::try_from(self.names.len()).expect("more than 2^32 symbols"));
        self.names.push(name.to_string());
        self.sym_index.insert(name.to_string(), s);
        s
    }

    /// The name of a symbol.
    pub fn name(&self, s: Sym) -> &str {
        &self.names[s.0 as usize]
    }

    /// The time symbol `t`.
    pub fn time(&self) -> Sym {
        Sym(0)
    }

    /// 0.
    pub fn zero(&self) -> Id {
        self.zero
    }

    /// 1.
    pub fn one(&self) -> Id {
        self.one
    }

    /// −1.
    pub(crate) fn minus_one(&self) -> Id {
        self.minus_one
    }

    /// An exact rational number.
    pub(crate) fn num(&mut self, value: BigRational) -> Id {
        self.intern(Node::Num(value))
    }

    /// An integer.
    pub(crate) fn int(&mut self, value: i64) -> Id {
        self.num(BigRational::from_integer(BigInt::from(value)))
    }

    /// The rational `n / d` (`d` must not be zero).
    pub fn ratio(&mut self, n: i64, d: i64) -> Id {
        self.num(BigRational::new(BigInt::from(n), BigInt::from(d)))
    }

    /// π.
    pub fn pi(&mut self) -> Id {
        self.intern(Node::Pi)
    }

    /// The `order`-th time derivative of symbol `s` (order 0 is the symbol itself).
    pub fn var(&mut self, s: Sym, order: u8) -> Id {
        self.intern(Node::Var(s, order))
    }

    /// The symbol named `name`, interning it if needed.
    pub fn sym(&mut self, name: &str) -> Id {
        let s = self.symbol(name);
        self.var(s, 0)
    }

    /// The number, if `id` is one.
    pub(crate) fn as_num(&self, id: Id) -> Option<&BigRational> {
        match self.node(id) {
            Node::Num(v) => Some(v),
            _ => None,
        }
    }

    /// The value of `id` as a float, if it is a number.
    pub fn number_value(&self, id: Id) -> Option<f64> {
        num_traits::ToPrimitive::to_f64(self.as_num(id)?)
    }

    /// Whether `id` is a number ≥ 0.
    pub fn is_nonnegative_constant(&self, id: Id) -> bool {
        self.as_num(id)
            .is_some_and(|v| !num_traits::Signed::is_negative(v))
    }

    /// Whether `id` is the number 0.
    pub fn is_zero(&self, id: Id) -> bool {
        id == self.zero
    }

    /// Pushes the children of a node onto `out` (no allocation, for traversals).
    pub(crate) fn push_children(&self, id: Id, out: &mut Vec<Id>) {
        match self.node(id) {
            Node::Num(_) | Node::Var(..) | Node::Pi => {}
            Node::Add(c) | Node::Mul(c) => out.extend_from_slice(c),
            Node::Pow(b, e) => {
                out.push(*b);
                out.push(*e);
            }
            Node::Func(_, a) => out.push(*a),
        }
    }

    /// Whether `pred` holds for any node of `root` (itself included). Walks without
    /// recursion, each shared node once, so bounded by the pool's size.
    pub fn any_node(&self, root: Id, mut pred: impl FnMut(&Node) -> bool) -> bool {
        let mut seen = rustc_hash::FxHashSet::default();
        let mut stack = vec![root];
        while let Some(n) = stack.pop() {
            if !seen.insert(n) {
                continue;
            }
            if pred(self.node(n)) {
                return true;
            }
            self.push_children(n, &mut stack);
        }
        false
    }

    /// Every distinct variable (symbol with derivative order) occurring in `id`, sorted by
    /// symbol then order.
    pub fn variables(&self, id: Id) -> Vec<(Sym, u8)> {
        let mut seen = rustc_hash::FxHashSet::default();
        let mut vars = Vec::new();
        let mut stack = vec![id];
        while let Some(n) = stack.pop() {
            if !seen.insert(n) {
                continue;
            }
            match self.node(n) {
                Node::Var(s, o) => vars.push((*s, *o)),
                _ => self.push_children(n, &mut stack),
            }
        }
        crate::sort::sort(&mut vars);
        vars.dedup();
        vars
    }

    /// Number of operations when printed as a tree (a rough size, like SymPy's `count_ops`):
    /// each binary +, −, ×, ÷, ^ and each function counts one.
    pub fn count_ops(&self, id: Id) -> usize {
        match self.node(id) {
            Node::Num(v) => usize::from(!v.is_integer()) + usize::from(v < &BigRational::zero()),
            Node::Var(..) | Node::Pi => 0,
            Node::Add(c) | Node::Mul(c) => {
                c.len() - 1 + c.iter().map(|&x| self.count_ops(x)).sum::<usize>()
            }
            Node::Pow(b, e) => 1 + self.count_ops(*b) + self.count_ops(*e),
            Node::Func(_, a) => 1 + self.count_ops(*a),
        }
    }
}
