//! End-to-end tests: the `impact` binary as users and scripts call it.

mod chain;
mod cli_errors;
mod cluster;
mod compare;
mod cost;
mod diagram;
mod docs;
mod explore;
mod run;
mod support;
mod sweep;
mod tracker;
