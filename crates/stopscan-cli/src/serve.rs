//! `stopscan serve`: the transport around [`stopscan::pipeline::serve::Server`]: lines on
//! standard input and output, or on TCP connections one after another.

use std::io::{BufRead, BufReader, Write};
use std::net::TcpListener;

use anyhow::Context;
use stopscan::pipeline::serve::message::{MAX_LINE, ProtocolError, Reply};
use stopscan::pipeline::serve::{ServeOptions, Server};

use crate::cli::{Global, ServeArgs};

pub(crate) fn run(a: &ServeArgs, _g: &Global) -> anyhow::Result<()> {
    let options = ServeOptions { max_scans: a.max_scans, fsync: a.fsync };
    let mut server = match (&a.journal, &a.resume) {
        (Some(j), None) => Server::with_journal(j, options)?,
        (None, Some(r)) => {
            let s = Server::resume(r, options)?;
            eprintln!(
                "resumed {} at step {}{}",
                r.display(),
                s.steps(),
                if s.is_done() { " (the session is over)" } else { "" }
            );
            s
        }
        _ => Server::new(options),
    };
    match &a.listen {
        None => {
            let stdin = std::io::stdin();
            serve_stream(&mut server, stdin.lock(), std::io::stdout().lock())
        }
        Some(addr) => {
            let listener =
                TcpListener::bind(addr).with_context(|| format!("cannot listen on {addr}"))?;
            let local = listener.local_addr()?;
            eprintln!("listening on {local}");
            for stream in listener.incoming() {
                let stream = match stream {
                    Ok(s) => s,
                    Err(e) => {
                        eprintln!("connection failed: {e}");
                        continue;
                    }
                };
                let reader = BufReader::new(stream.try_clone()?);
                if let Err(e) = serve_stream(&mut server, reader, stream) {
                    // A journal that cannot be written ends the server; a dropped connection
                    // only this connection.
                    if e.downcast_ref::<stopscan::pipeline::serve::ServeError>().is_some() {
                        return Err(e);
                    }
                    eprintln!("connection closed: {e}");
                }
                if server.is_done() {
                    break;
                }
            }
            Ok(())
        }
    }
}

/// Answers every line of `input` on `output` until the input ends.
fn serve_stream(
    server: &mut Server,
    mut input: impl BufRead,
    mut output: impl Write,
) -> anyhow::Result<()> {
    let mut buf = Vec::new();
    loop {
        buf.clear();
        let n = std::io::Read::take(&mut input, MAX_LINE as u64 + 1).read_until(b'\n', &mut buf)?;
        if n == 0 {
            return Ok(());
        }
        let reply = if buf.len() > MAX_LINE {
            // Skip the rest of the line.
            let mut rest = Vec::new();
            while !buf.ends_with(b"\n") {
                rest.clear();
                if std::io::Read::take(&mut input, MAX_LINE as u64).read_until(b'\n', &mut rest)?
                    == 0
                {
                    break;
                }
                buf.clone_from(&rest);
            }
            let e = ProtocolError {
                field: None,
                message: format!("line longer than {MAX_LINE} bytes; it was skipped"),
            };
            Reply::error(None, e).to_line()
        } else {
            match std::str::from_utf8(&buf) {
                Ok(line) => {
                    let line = line.trim_end_matches(['\n', '\r']);
                    if line.trim().is_empty() {
                        continue;
                    }
                    server.handle(line)?
                }
                Err(e) => Reply::error(
                    None,
                    ProtocolError { field: None, message: format!("not UTF-8: {e}") },
                )
                .to_line(),
            }
        };
        output.write_all(reply.as_bytes())?;
        output.write_all(b"\n")?;
        output.flush()?;
    }
}
