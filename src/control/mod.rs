//! Path-following controllers: they turn a pose and a trajectory into a twist.
