//! A small ST7789 driver for band rendering: the panel's set-up, and a
//! `DrawTarget` per core whose `fill_contiguous` hands a band to the DMA and
//! returns while it is sent.
//!
//! After the set-up ([`init`], 8-bit SPI frames) the bus sends 16-bit
//! frames: an RGB565 pixel is one frame, most significant byte first, as
//! the panel wants it, so a band is copied to the transmit buffer as it is.
//! A command byte goes as the frame `0x00cc` (DC low): a NOP (0x00), then
//! the command; the address window's parameters are two 16-bit frames per
//! axis (start, end).
//!
//! Each core has one transmit buffer. `fill_contiguous` waits until that
//! buffer is free (its previous band sent), copies the band into it, and
//! queues it on the [`Link`]: the shared bus, DMA channel and DC/CS pins
//! behind a `critical_section::Mutex` (on the RP2040 a hardware spinlock,
//! so both cores can share it). The link sends one band at a time: it
//! waits for the band in flight, sets the next band's address window
//! (CASET, RASET, RAMWR: a few frames, by the CPU) and starts its DMA. The
//! caller then draws its next band into its colour band while this one goes
//! out: two colour bands per core, one drawn, one sent.

use core::cell::RefCell;

use critical_section::Mutex;
use embedded_graphics::pixelcolor::{IntoStorage, Rgb565};
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use embedded_hal::delay::DelayNs;
use embedded_hal::digital::OutputPin;
use embedded_hal::spi::SpiBus;
use rp_pico::hal::dma::single_buffer::{Config, Transfer};
use rp_pico::hal::dma::{SingleChannel, WriteTarget};

/// The panel's size in pixels.
pub const WIDTH: u32 = 240;
/// The panel's size in pixels.
pub const HEIGHT: u32 = 240;

/// A core's transmit buffer: `N` pixels.
pub type TxBuffer<const N: usize> = &'static mut [u16; N];

/// Resets the panel and sets it up for RGB565 pixels (the sequence of the
/// `mipidsi` crate's ST7789 model), over 8-bit SPI frames: hardware reset,
/// sleep out, memory access order (none: rows top to bottom), colour
/// inversion on (ST7789 IPS modules need it: without it black shows white),
/// 16 bits per pixel, normal mode, display on. CS is left high.
pub fn init<S, P, D>(spi: &mut S, dc: &mut P, cs: &mut P, rst: &mut P, delay: &mut D)
where
    S: SpiBus<u8>,
    P: OutputPin,
    D: DelayNs,
{
    let _ = cs.set_high();
    let _ = rst.set_low();
    delay.delay_us(20);
    let _ = rst.set_high();
    delay.delay_ms(150);
    let _ = cs.set_low();
    for (c, params, wait_ms) in [
        (0x11, &[][..], 10), // SLPOUT
        (0x36, &[0x00], 0),  // MADCTL
        (0x21, &[], 0),      // INVON
        (0x3A, &[0x55], 10), // COLMOD: 16 bits per pixel
        (0x13, &[], 10),     // NORON
        (0x29, &[], 120),    // DISPON
    ] {
        command(spi, dc, c, params);
        delay.delay_ms(wait_ms);
    }
    let _ = spi.flush();
    let _ = cs.set_high();
}

/// A command and its parameters, in frames of `W` (a 16-bit command frame
/// is a NOP and the command), waiting for the bus to be idle before each
/// change of DC.
fn command<W: From<u8> + Copy + 'static, S: SpiBus<W>, P: OutputPin>(
    spi: &mut S,
    dc: &mut P,
    c: u8,
    params: &[W],
) {
    let _ = spi.flush();
    let _ = dc.set_low();
    let _ = spi.write(&[W::from(c)]);
    let _ = spi.flush();
    let _ = dc.set_high();
    let _ = spi.write(params);
}

/// What a [`Sender`] could not do.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LcdError {
    /// An area wider than a transmit buffer.
    TooWide,
}

/// The bus (16-bit frames), the DMA channel and the DC and CS pins, shared
/// by the cores; at most one band in flight.
pub struct Link<CH: SingleChannel, S: WriteTarget<TransmittedWord = u16>, P, const N: usize> {
    /// The channel and the bus when no band is in flight.
    idle: Option<(CH, S)>,
    /// The band in flight and which core's buffer it is.
    sending: Option<(Transfer<CH, TxBuffer<N>, S>, usize)>,
    /// Buffers whose band has gone out, by core.
    done: [Option<TxBuffer<N>>; 2],
    dc: P,
    cs: P,
}

/// The link as a static: `critical_section::Mutex<RefCell<Option<Link>>>`.
pub type Shared<CH, S, P, const N: usize> = Mutex<RefCell<Option<Link<CH, S, P, N>>>>;

impl<CH, S, P, const N: usize> Link<CH, S, P, N>
where
    CH: SingleChannel,
    S: WriteTarget<TransmittedWord = u16> + SpiBus<u16>,
    P: OutputPin,
{
    /// A link over `spi` (16-bit frames, after [`init`]) and `channel`.
    pub fn new(channel: CH, spi: S, dc: P, cs: P) -> Self {
        Link {
            idle: Some((channel, spi)),
            sending: None,
            done: [None, None],
            dc,
            cs,
        }
    }

    /// If the band in flight has gone out, ends it: its buffer back to its
    /// core, the channel and the bus idle, CS high.
    fn poll(&mut self) {
        if let Some((t, core)) = self.sending.take() {
            if !t.is_done() {
                self.sending = Some((t, core));
                return;
            }
            let (ch, buf, mut spi) = t.wait();
            // The DMA has filled the FIFO; wait for the last frames.
            let _ = spi.flush();
            let _ = self.cs.set_high();
            self.done[core] = Some(buf);
            self.idle = Some((ch, spi));
        }
    }

    /// Sends the first `n` pixels of `buf` to `area` if the bus is idle, or
    /// gives `buf` back. A whole buffer goes by DMA and is in flight when
    /// this returns; a shorter block (which the DMA, sending the whole
    /// buffer, would wrap over the window's start) is written by the CPU.
    fn try_send(
        &mut self,
        buf: TxBuffer<N>,
        n: usize,
        area: &Rectangle,
        core: usize,
    ) -> Result<(), TxBuffer<N>> {
        self.poll();
        let Some((ch, mut spi)) = self.idle.take() else {
            return Err(buf);
        };
        let (x, y) = (area.top_left.x as u16, area.top_left.y as u16);
        let (w, h) = (area.size.width as u16, area.size.height as u16);
        let _ = self.cs.set_low();
        command(&mut spi, &mut self.dc, 0x2A, &[x, x + w - 1]); // CASET
        command(&mut spi, &mut self.dc, 0x2B, &[y, y + h - 1]); // RASET
        if n == N {
            // RAMWR, then the pixels by DMA (DC stays high).
            command(&mut spi, &mut self.dc, 0x2C, &[]);
            self.sending = Some((Config::new(ch, buf, spi).start(), core));
        } else {
            command(&mut spi, &mut self.dc, 0x2C, &buf[..n]);
            let _ = spi.flush();
            let _ = self.cs.set_high();
            self.done[core] = Some(buf);
            self.idle = Some((ch, spi));
        }
        Ok(())
    }
}

/// A core's end of the [`Link`]: a `DrawTarget` of the whole panel that
/// sends what it is given in blocks of rows, each while the caller goes on.
pub struct Sender<CH, S, P, const N: usize>
where
    CH: SingleChannel + 'static,
    S: WriteTarget<TransmittedWord = u16> + 'static,
    P: 'static,
{
    link: &'static Shared<CH, S, P, N>,
    core: usize,
    buf: Option<TxBuffer<N>>,
}

impl<CH, S, P, const N: usize> Sender<CH, S, P, N>
where
    CH: SingleChannel,
    S: WriteTarget<TransmittedWord = u16> + SpiBus<u16>,
    P: OutputPin,
{
    /// Core `core`'s (0 or 1) sender, with its transmit buffer. `link`
    /// must hold the link before anything is drawn.
    pub fn new(link: &'static Shared<CH, S, P, N>, core: usize, buf: TxBuffer<N>) -> Self {
        Sender {
            link,
            core: core & 1,
            buf: Some(buf),
        }
    }

    /// This core's buffer, once the band it last held has gone out.
    fn buffer(&mut self) -> TxBuffer<N> {
        loop {
            if let Some(b) = self.buf.take() {
                return b;
            }
            self.buf = critical_section::with(|cs| {
                let mut link = self.link.borrow_ref_mut(cs);
                let link = link.as_mut()?;
                link.poll();
                link.done[self.core].take()
            });
        }
    }

    /// Queues the first `n` pixels of `buf` for `area`, waiting for the bus.
    fn send(&mut self, buf: TxBuffer<N>, n: usize, area: &Rectangle) {
        let mut buf = Some(buf);
        while let Some(b) = buf.take() {
            buf = critical_section::with(|cs| match self.link.borrow_ref_mut(cs).as_mut() {
                Some(link) => link.try_send(b, n, area, self.core).err(),
                None => None,
            });
        }
    }
}

impl<CH, S, P, const N: usize> OriginDimensions for Sender<CH, S, P, N>
where
    CH: SingleChannel,
    S: WriteTarget<TransmittedWord = u16>,
{
    fn size(&self) -> Size {
        Size::new(WIDTH, HEIGHT)
    }
}

impl<CH, S, P, const N: usize> DrawTarget for Sender<CH, S, P, N>
where
    CH: SingleChannel,
    S: WriteTarget<TransmittedWord = u16> + SpiBus<u16>,
    P: OutputPin,
{
    type Color = Rgb565;
    type Error = LcdError;

    /// Pixel by pixel, each its own window: slow, for odd pixels only.
    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), LcdError>
    where
        I: IntoIterator<Item = Pixel<Rgb565>>,
    {
        for Pixel(p, c) in pixels {
            self.fill_contiguous(&Rectangle::new(p, Size::new(1, 1)), [c])?;
        }
        Ok(())
    }

    /// The area's pixels (row by row) in blocks of as many whole rows as a
    /// transmit buffer holds: one block for a band of `Bands` when the
    /// buffer holds a band. Pixels outside the panel are dropped.
    fn fill_contiguous<I>(&mut self, area: &Rectangle, colors: I) -> Result<(), LcdError>
    where
        I: IntoIterator<Item = Rgb565>,
    {
        let visible = area.intersection(&self.bounding_box());
        if visible.size != area.size {
            let inside = area
                .points()
                .zip(colors)
                .filter(|(p, _)| visible.contains(*p))
                .map(|(p, c)| Pixel(p, c));
            return self.draw_iter(inside);
        }
        let (w, h) = (area.size.width as usize, area.size.height as usize);
        if w == 0 || h == 0 {
            return Ok(());
        }
        let rows_per_block = N / w;
        if rows_per_block == 0 {
            return Err(LcdError::TooWide);
        }
        let mut colors = colors.into_iter();
        let mut y = 0;
        while y < h {
            let rows = rows_per_block.min(h - y);
            let n = w * rows;
            let buf = self.buffer();
            for (dst, c) in buf[..n].iter_mut().zip(colors.by_ref()) {
                *dst = c.into_storage();
            }
            let block = Rectangle::new(
                area.top_left + Point::new(0, y as i32),
                Size::new(w as u32, rows as u32),
            );
            self.send(buf, n, &block);
            y += rows;
        }
        Ok(())
    }
}
